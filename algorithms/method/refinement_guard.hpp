// The final refinement may not complicate the topology the evolution found (ours; docs/design.md §1 leaves
// the final refinement's safeguards open). The evolution decides the topology: it moves the zero set
// continuously, pinching necks and opening holes where the data ask for it. The final refinement is a
// direct fit (final_refinement.hpp): where a part is thinner than about two cells of the refined
// T-mesh, data rows on both of its sides pull f to zero across the whole part and the fit can sever it
// (docs/design.md §8: the armadillo's wrists and ankles) or open a spurious handle. So the refined level set is kept only if its
// zero set has no more components and no larger genus than the evolved one; otherwise the fit is
// scaled back, f_alpha = f_transferred + alpha (f_fitted - f_transferred) for the next alpha of a
// decreasing list, down to alpha = 0 (the evolved f on the refined T-mesh, taken without a check).
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "algorithms/tspline/tspline.hpp"

namespace dtsl {

/// Components and genus (summed over the components) of a zero set's mesh.
struct ZeroSetTopology {
  int components = 0;
  double genus = 0.0;  ///< NaN for an open mesh (metrics.hpp)
};

/// Whether `after` is no more complicated than `before`: no more components; if `before` is closed
/// (finite genus), `after` closed too and of no larger genus.
bool no_more_complex(const ZeroSetTopology& after, const ZeroSetTopology& before);

/// Meshes a candidate level set and returns its topology, or nothing when it cannot be meshed. `alpha`
/// names the candidate (-1: the evolved reference, else its fraction of the fit), e.g. for a log.
using TopologyOf = std::function<std::optional<ZeroSetTopology>(const TSpline& level_set, double alpha)>;

struct GuardedRefinement {
  TSpline level_set;           ///< the candidate kept
  double alpha = 1.0;          ///< its fraction of the fit (1: the whole fit kept)
  nlohmann::json summary;      ///< reference topology, every candidate tried, the choice and why
};

/// Chooses among f_alpha (alphas: decreasing, in (0, 1], 1 first; alpha = 0 is the last resort) the
/// first whose topology is no more complex than that of `evolved` (the level set before the final
/// refinement). `transferred` is the evolved f on the refined T-mesh (same basis as `fitted`). When the
/// evolved level set itself cannot be meshed there is no reference: the fitted one is kept, and the
/// summary says so. `transferred` must be ordered as `fitted`'s basis (final_refinement.cpp fits the
/// transferred coefficients in place, so it is); AlgorithmError on a count that differs, or alphas not
/// decreasing from 1 within (0, 1].
GuardedRefinement guard_refinement_topology(const TSpline& evolved, const TSpline& fitted,
                                            const std::vector<double>& transferred, const TopologyOf& topology_of,
                                            const std::vector<double>& alphas = {1.0, 0.5, 0.25});

}  // namespace dtsl
