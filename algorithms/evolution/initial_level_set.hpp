// The initial level set of the evolution (DESIGN.md §1): f_0 = signed distance to a sphere enclosing
// every data point — centre at the data's bounding-box centre, radius radius_factor (1.1) x the
// largest distance from that centre to a point — put into coefficients by quasi-interpolation
// (c_i = f_0 at the Greville point of B_i).
//
// In the [-1,1]^3 frame the sphere may reach past the T-mesh's domain (radius up to 1.1 sqrt 3 > 1.25
// when the data fill the box's corners): the zero set then starts cut off by the domain, with the
// domain's boundary inside f < 0. That is harmless — f is defined (clamped) everywhere, the zero set
// is sampled inside the domain only, and the inside region leaves the boundary as the surface moves
// in — but a polygonizer run on the very first iterates sees an open surface.
#pragma once

#include <memory>
#include <vector>

#include "algorithms/tspline/tspline.hpp"

namespace dtsl {

struct EnclosingSphere {
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;
};

/// AlgorithmError for no points or radius_factor < 1 (the sphere would not enclose the data).
EnclosingSphere enclosing_sphere(const std::vector<Vec3>& points, double radius_factor);

/// The quasi-interpolant of the sphere's signed distance |x - centre| - radius on `basis`.
TSpline initial_level_set(std::shared_ptr<const TSplineBasis> basis, const EnclosingSphere& sphere);

}  // namespace dtsl
