#include "algorithms/evolution/thin_points.hpp"

namespace dtsl {

std::vector<Vec3> thin_points(const std::vector<Vec3>& points, std::size_t max_points) {
  const std::size_t n = points.size();
  if (max_points == 0 || n <= max_points) return points;
  std::vector<Vec3> kept;
  kept.reserve(max_points);
  // Point k is kept when floor(k m / n) steps up: exactly m points, evenly spaced in input order.
  for (std::size_t k = 0; k < n; ++k)
    if ((k + 1) * max_points / n != k * max_points / n) kept.push_back(points[k]);
  return kept;
}

}  // namespace dtsl
