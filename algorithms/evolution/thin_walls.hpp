// Thin walls keep their inside (ours). Where the data sample the two faces of a wall or plate no more
// than a few cells thick, the two fronts that the evolution brings onto them share the wall's control
// points, and the spline's minimum between them is shallow: a step's least-squares fit (velocity,
// distance-field and smoothness rows pulling on the same controls) lifts it through zero somewhere and
// punches a tunnel through the wall, a handle the data do not have. The noisy rocker arm of the dev half
// gained its handle this way, at a spot where the wall is 2.8 finest cells thick and the minimum had
// risen to -0.007 (docs/design.md §8).
//
// The start (carve or wrap, data_carving.hpp, data_wrap.hpp) already says where the walls are: its
// level set wraps each face from its own side, so its gradient at a data point is that face's outward
// normal. A wall is a pair of data points p, q whose normals face away from each other
// (n_p . n_q <= -1/2), q behind p (within 45 degrees of -n_p), close (at most kMaxWallCells leaf sides)
// and with no face turned sideways on the march between them. Where the start spans a concave corner, a
// march from p can cross the part, leave it through the face the start covered over (its normal points
// out to the start's surface, sideways to the march) and cross the corner's empty space to a face
// beyond that does face away; such a pair's row held the corner's front where the start left it, 2.5
// spacings off the data (the rocker arm, docs/design.md §8). So a march ends at a face it passes
// through (a point within half a leaf of its path) that is turned sideways or the same way
// (0 <= n_p . n_q < 1/2; p's own face curving along the march, above 1/2, does not count), and goes at
// most one leaf past a face turned partly away (the far face with tilted normals). The middle w =
// (p + q) / 2 should stay inside by the depth t / 4 (t = |p - q|): the minimum of the smoothest profile
// across the wall that leaves both faces with unit slope, f(s) = (s^2 - t^2 / 4) / t. Where f(w) has
// risen above -t / 4, the step gets a row f'(w) = (-t / 4 - f(w)) / dt, weighted as one zero-set row.
// The walls are looked for from every data point, so a wall sampled on both faces has a middle (and a
// row) from each side. A membrane over a through-hole has no data across it, so no wall holds it: the
// evolution still opens the holes the start missed.
#pragma once

#include <vector>

#include "algorithms/evolution/data_distance.hpp"
#include "algorithms/tspline/octree.hpp"
#include "framework/core/implicit.hpp"
#include "framework/core/types.hpp"

namespace dtsl {

/// Walls thicker than this many leaf sides (of the start's T-mesh, at the data point) are not looked
/// for: their middle lies deep enough inside without help, and the rows would never be active.
constexpr double kMaxWallCells = 4.0;

/// One entry per data point that found the other face of its wall.
struct ThinWalls {
  std::vector<Vec3> middle;   ///< w = (p + q) / 2
  std::vector<double> depth;  ///< t / 4
  std::size_t size() const { return middle.size(); }
  bool empty() const { return middle.empty(); }
};

/// The walls of `points` as `start` (a level set that encloses the data, negative inside) orients them:
/// for each point p with a non-zero gradient, the first point q met on a march along -n_p (quarter-leaf
/// steps of `tmesh`, up to kMaxWallCells leaf sides) that lies within 45 degrees of -n_p, faces away
/// (n_p . n_q <= -1/2) and is no farther than that, unless the march passed through another face first
/// (above). `data` is the distance to `points`. OpenMP-parallel;
/// the same walls, in point order, for any thread count.
ThinWalls thin_walls(const std::vector<Vec3>& points, const DataDistance& data, const ImplicitFunction& start,
                     const Octree& tmesh);

/// The rows of one step: the middles where f has risen above -depth, and their targets for f'
/// ((-depth - f(w)) / dt). OpenMP-parallel, in wall order.
struct WallRows {
  std::vector<Vec3> position;
  std::vector<double> target;
};
WallRows wall_rows(const ThinWalls& walls, const ImplicitFunction& f, double dt);

}  // namespace dtsl
