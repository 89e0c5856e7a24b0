// The data the level-set stage works on. Its T-mesh stops at max_depth, and what decides the T-mesh
// and the fit is how many points each finest cell holds, up to a few (tmesh points_per_cell, the
// coarse-to-fine rounds' fine_points_per_cell = 4); beyond that, more points in a cell add cost —
// distances, the final refinement's value rows — and no detail the T-spline can carry. The detail of
// every point comes back in the displacement (paper §3), which sees all of them.
#pragma once

#include <cstddef>
#include <vector>

#include "framework/core/types.hpp"

namespace dtsl {

/// At most `max_points` of `points` (all of them, as given, if max_points is 0 or not smaller): in every
/// cube of side `cell` (a grid anchored at the origin), c points spread over the cube, with c the largest
/// cap that keeps the total within max_points (at least 1: with more occupied cells than max_points, one
/// point per cell, the one nearest the cell's centre). Sparse cells keep all their points, so sampling
/// density differences and holes survive; only the redundancy of dense cells goes. The result, points
/// and order, depends on the points only, not on their order in the input (a scanner's scan lines).
/// AlgorithmError for cell <= 0.
std::vector<Vec3> thin_points(const std::vector<Vec3>& points, std::size_t max_points, double cell);

}  // namespace dtsl
