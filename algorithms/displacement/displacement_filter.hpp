// The displacement filter (paper §3.2) as plugins: each vertex's d(v) is a weighted sum of the data's
// displacements d_k over the foot points near it (foot_neighbourhood.hpp). Registered filters:
//   gaussian  the paper's Gaussian mean, sigma_factor x the mean edge length wide;
//   adaptive  (ours, the default) measures the data's noise (noise_estimate.hpp): on noisy data each
//             vertex picks its own width by the intersection of confidence intervals and fits a local
//             linear function over the wider widths (Katkovnik's LPA-ICI); on noise-free data the base
//             width is at least the data's median spacing and fits a plane (data sparser than the mesh
//             ripple at the paper's width), and the paper's narrow mean then follows the creases
//             through the fine residual passes (residual_passes.hpp). Between sparse data the level
//             set's own shape is not evidence: by default (SparseGaps::margin) a vertex with no data
//             within the paper's support is a hole, faired from the supported ones (hole_treatment.hpp)
//             rather than carried along by a plane fitted to data a spacing away, except within the
//             wide filter's reach of a hole (farther from the data than that reach, measured in the
//             local spacing at its edge), where the fit carries the data's surface across its edge.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "algorithms/displacement/foot_neighbourhood.hpp"
#include "algorithms/displacement/noise_estimate.hpp"
#include "algorithms/displacement/projection.hpp"
#include "framework/config/options.hpp"
#include "framework/core/types.hpp"
#include "framework/registry/registry.hpp"

namespace dtsl {

/// What a filter measured of the data: measured once per run, the refine-on-flip rounds reuse it.
struct DataScale {
  double noise_sigma = 0.0;               ///< noise along the normal (frame units); 0: noise-free
  double spacing = 0.0;                   ///< the data's median spacing; 0: not measured
  std::optional<NoiseEstimate> estimate;  ///< the estimate the figures came from, if one was made
  double seconds = 0.0;
};

/// What becomes of the vertices with no data within the paper's support where the `adaptive` filter fits a
/// plane over the wider data spacing (DisplacementOptions::gaps).
enum class SparseGaps { fit, margin };
/// The names DisplacementOptions::gaps accepts, in the enum's order.
inline constexpr const char* kSparseGapsNames[] = {"fit", "margin"};
std::optional<SparseGaps> sparse_gaps_from_name(const std::string& name);

/// What a filter sees: the base mesh M_0, the projection of the data onto it, and grad f's normals.
struct FilterInput {
  const TriangleMesh& base;
  const ProjectionResult& projection;
  const std::vector<Vec3>& points;                   ///< the data, p_k
  const std::vector<Vec3>& normals;                  ///< per base vertex, unit
  const std::vector<std::vector<int>>& neighbours;   ///< per base vertex, its one-ring
  double mean_edge = 0.0;                            ///< the base mesh's mean edge length
  double paper_width = 0.0;                          ///< sigma_factor x mean_edge
  const DataScale& scale;
  SparseGaps gaps = SparseGaps::margin;
};

/// Each vertex's filter.
struct VertexFilters {
  std::vector<FilterTaps> taps;        ///< empty for a hole vertex (no data within the support)
  std::vector<char> known;             ///< 1 where taps are set
  std::vector<double> width;           ///< the width each vertex's filter took
  std::vector<int> degree;             ///< the degree of the local polynomial it fits (0: a mean)
  std::vector<double> one_sidedness;   ///< the base filter's FootNeighbourhoods::one_sidedness
  double base_width = 0.0;             ///< the narrowest width
  bool base_fits = false;              ///< noise-free data, base width fitting a plane: the fine passes apply
  std::unique_ptr<FootNeighbourhoods> feet;  ///< the feet the taps came from (the fine passes' narrow taps)
};

class DisplacementFilter {
 public:
  virtual ~DisplacementFilter() = default;
  Options& options() { return options_; }
  /// The data's noise and spacing, as far as this filter needs them.
  virtual DataScale measure(const std::vector<Vec3>& points) const = 0;
  /// Throws AlgorithmError when no foot point is valid.
  virtual VertexFilters build(const FilterInput& in) const = 0;

 private:
  NoOptions options_;
};

Registry<DisplacementFilter>& displacement_filters();

/// The ladder of widths a filter tries and whether the base width fits a plane (filter_taps.cpp).
struct FilterLadder {
  std::vector<double> widths;  ///< increasing; more than one: ICI picks per vertex (noisy data)
  bool base_fits = false;
  double noise_sigma = 0.0;
  /// A vertex is a hole unless the hole test passes at this width too (0: the base width's test alone).
  double support_width = 0.0;
};
/// Every vertex's taps over `ladder` (ICI where it has several widths). Throws AlgorithmError when no
/// foot point is valid.
VertexFilters build_vertex_filters(const FilterInput& in, const FilterLadder& ladder);

}  // namespace dtsl
