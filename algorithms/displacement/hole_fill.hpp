// Displacement values for vertices with no data near them (holes): a harmonic fill over the mesh graph
// (docs/design.md §3, *ours*; the paper's Gaussian filter leaves such vertices undefined). The filled values
// interpolate the known ones at the hole's rim, so the displaced surface spans the hole without a step
// or a crease where data ends, instead of dropping back to the base surface (d = 0).
#pragma once

#include <vector>

namespace dtsl {

struct HoleFillReport {
  std::size_t unknown = 0;     ///< vertices filled
  std::size_t unreached = 0;   ///< unknown vertices in components with no known vertex (set to 0)
};

/// Solves the graph Laplace equation (uniform weights) sum_{j ~ i} (d_i - d_j) = 0 for every vertex
/// with known[i] == 0, with the known values fixed: a sparse SPD solve (Eigen's SimplicialLDLT).
/// `neighbours[i]`: the vertices adjacent to i. `values` holds the known values and receives the rest.
HoleFillReport harmonic_fill(const std::vector<std::vector<int>>& neighbours, const std::vector<char>& known,
                             std::vector<double>& values);

}  // namespace dtsl
