// The data the level-set stage works on. Its T-mesh stops at max_depth (cells of 2^-max_depth of the
// domain), so beyond some tens of thousands of points more data adds cost — distances, the final
// refinement's value rows, the T-mesh's points per cell — but no detail the T-spline could carry; the
// detail of the remaining points comes back in the displacement (paper §3), which sees all of them.
#pragma once

#include <cstddef>
#include <vector>

#include "framework/core/types.hpp"

namespace dtsl {

/// At most `max_points` of `points` (all of them if max_points is 0 or not smaller): every k-th in input
/// order with a fractional stride, so the choice is deterministic and spreads over the whole input.
std::vector<Vec3> thin_points(const std::vector<Vec3>& points, std::size_t max_points);

}  // namespace dtsl
