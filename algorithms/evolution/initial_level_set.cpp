#include "algorithms/evolution/initial_level_set.hpp"

#include <algorithm>

#include "framework/core/error.hpp"

namespace dtsl {

double EnclosingSurface::operator()(const Vec3& x) const {
  const double sphere = (x - centre).norm() - radius;
  if (!clipped) return sphere;
  // Signed distance to the box: outside, the distance to it; inside, minus the distance to its faces.
  const Vec3 half = 0.5 * box.extent();
  const Vec3 q = (x - box.center()).cwiseAbs() - half;
  const double box_distance = q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
  return std::max(sphere, box_distance);
}

EnclosingSurface enclosing_surface(const std::vector<Vec3>& points, double radius_factor, double box_margin) {
  if (points.empty()) throw AlgorithmError("initial level set: no data points");
  if (!(radius_factor >= 1.0))
    throw AlgorithmError("initial level set: radius factor must be >= 1 to enclose the data");
  EnclosingSurface s;
  const BoundingBox box = bounding_box(points);
  s.centre = box.center();
  double largest = 0.0;
  for (const Vec3& p : points) largest = std::max(largest, (p - s.centre).norm());
  s.radius = radius_factor * largest;
  if (box_margin > 0.0) {
    s.clipped = true;
    s.box.min = box.min - Vec3::Constant(box_margin);
    s.box.max = box.max + Vec3::Constant(box_margin);
  }
  return s;
}

TSpline initial_level_set(std::shared_ptr<const TSplineBasis> basis, const EnclosingSurface& surface) {
  return quasi_interpolant(std::move(basis), [&surface](const Vec3& x) { return surface(x); });
}

}  // namespace dtsl
