// The initial level set of the evolution (DESIGN.md §1): f_0 = signed distance to a sphere enclosing
// every data point — centre at the data's bounding-box centre, radius radius_factor (1.1) x the
// largest distance from that centre to a point — put into coefficients by quasi-interpolation
// (c_i = f_0 at the Greville point of B_i).
//
// Clipping (ours): in the [-1,1]^3 frame that sphere reaches past the T-mesh's domain whenever the data
// fill the corners of their box (radius up to 1.1 sqrt 3 = 1.9 > 1 + margin = 1.25). The zero set is
// then cut off by the domain's faces, the inside region touches the boundary, and the evolution first
// has to peel it off the faces — slowly, and leaving pockets of f < 0 stuck on the boundary. So the
// sphere is intersected with the data's bounding box grown by box_margin on every side (f_0 =
// max(sphere distance, box distance), still a function whose zero set encloses every point, inside
// the domain as long as box_margin < margin). For data that already fit in the sphere inside the
// box, nothing changes. box_margin <= 0 disables the clipping (the DESIGN.md sphere alone).
#pragma once

#include <memory>
#include <vector>

#include "algorithms/tspline/tspline.hpp"

namespace dtsl {

struct EnclosingSurface {
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;
  bool clipped = false;  ///< intersect the sphere with `box`
  BoundingBox box;
  /// Signed distance (an exact one for the sphere alone; max of the two for the intersection, exact
  /// outside both and a lower bound of the true distance elsewhere).
  double operator()(const Vec3& x) const;
};

/// The sphere of DESIGN.md §1, clipped to the data's box grown by box_margin when box_margin > 0.
/// AlgorithmError for no points or radius_factor < 1 (the sphere would not enclose the data).
EnclosingSurface enclosing_surface(const std::vector<Vec3>& points, double radius_factor, double box_margin);

/// The quasi-interpolant of the surface's signed distance on `basis`.
TSpline initial_level_set(std::shared_ptr<const TSplineBasis> basis, const EnclosingSurface& surface);

}  // namespace dtsl
