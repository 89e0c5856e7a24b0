#include "algorithms/evolution/initial_level_set.hpp"

#include <algorithm>

#include "framework/core/error.hpp"

namespace dtsl {

EnclosingSphere enclosing_sphere(const std::vector<Vec3>& points, double radius_factor) {
  if (points.empty()) throw AlgorithmError("initial level set: no data points");
  if (!(radius_factor >= 1.0))
    throw AlgorithmError("initial level set: radius factor must be >= 1 to enclose the data");
  EnclosingSphere s;
  s.centre = bounding_box(points).center();
  double largest = 0.0;
  for (const Vec3& p : points) largest = std::max(largest, (p - s.centre).norm());
  s.radius = radius_factor * largest;
  return s;
}

TSpline initial_level_set(std::shared_ptr<const TSplineBasis> basis, const EnclosingSphere& sphere) {
  return quasi_interpolant(std::move(basis),
                           [&sphere](const Vec3& x) { return (x - sphere.centre).norm() - sphere.radius; });
}

}  // namespace dtsl
