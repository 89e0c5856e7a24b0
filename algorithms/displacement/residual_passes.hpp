// Residual passes (ours; Van Cittert's iteration): a filter's mean of the d_k is biased wherever d
// varies across it (a base surface tilted against the data, a corner). Each pass measures every point's
// remaining offset r_k = (p_k - q'_k) . n_k from the displaced mesh (q'_k: the foot point carried along
// with its triangle) and adds the filtered r_k to d. The fine passes then add the paper's narrow
// Gaussian mean of what a plane fitted over the data's spacing left (displacement_filter.hpp,
// `adaptive` on noise-free data): on smooth parts almost nothing, at a crease the kink the plane rounded.
#pragma once

#include <vector>

#include "algorithms/displacement/displacement_filter.hpp"
#include "algorithms/displacement/projection.hpp"
#include "framework/core/types.hpp"

namespace dtsl {

/// d[v] += sum of taps[v]'s weights x values (d unchanged where taps[v] is empty).
void add_filtered(const std::vector<FilterTaps>& taps, const std::vector<double>& values, std::vector<double>& d);

struct ResidualPassReport {
  int passes = 0;              ///< residual passes made
  int fine_passes = 0;         ///< fine passes made
  std::size_t fine_vertices = 0;  ///< vertices the fine passes moved
  double residual_rms = -1.0;  ///< RMS of the points' offsets from the final mesh (noisy data; -1: not measured)
};

/// `passes` residual passes with `filters`, then (where filters.base_fits and the paper's width is
/// narrower than the base width) `fine_passes` with the paper's Gaussian mean `paper_width` wide.
/// `normals`: the base vertices' unit normals, along which d moves them.
ResidualPassReport apply_residual_passes(const TriangleMesh& base, const ProjectionResult& projection,
                                         const std::vector<Vec3>& points, const std::vector<Vec3>& normals,
                                         const VertexFilters& filters, double paper_width, int passes,
                                         int fine_passes, bool noisy, std::vector<double>& d);

}  // namespace dtsl
