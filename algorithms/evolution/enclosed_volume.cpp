#include "algorithms/evolution/enclosed_volume.hpp"

#include <algorithm>

#include "framework/core/error.hpp"

namespace dtsl {

EnclosureCheck check_enclosure(const std::vector<Vec3>& points, const std::vector<double>& local_spacing,
                               double median_spacing, const std::function<double(const Vec3&)>& signed_distance,
                               int max_tested) {
  if (local_spacing.size() != points.size())
    throw AlgorithmError("enclosure check: " + std::to_string(local_spacing.size()) + " spacings for " +
                         std::to_string(points.size()) + " points");
  if (max_tested < 1) throw AlgorithmError("enclosure check: max_tested must be positive");
  std::vector<Vec3> directions;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z) directions.push_back(Vec3(x, y, z).normalized());
  const std::size_t stride = std::max<std::size_t>(1, (points.size() + max_tested - 1) / std::size_t(max_tested));
  std::vector<std::size_t> tested;
  for (std::size_t k = 0; k < points.size(); k += stride) tested.push_back(k);
  std::vector<char> enclosed(tested.size(), 0);
#pragma omp parallel for schedule(dynamic, 16)
  for (long i = 0; i < long(tested.size()); ++i) {
    const std::size_t k = tested[std::size_t(i)];
    const double s = std::max(local_spacing[k], median_spacing);
    for (const double t : {0.75 * s, 1.5 * s, 3.0 * s}) {
      for (const Vec3& u : directions)
        if (signed_distance(points[k] + t * u) <= -kEnclosedDepthSpacings * median_spacing) {
          enclosed[std::size_t(i)] = 1;
          break;
        }
      if (enclosed[std::size_t(i)]) break;
    }
  }
  EnclosureCheck check;
  check.tested = int(tested.size());
  check.unenclosed = int(std::count(enclosed.begin(), enclosed.end(), 0));
  return check;
}

}  // namespace dtsl
