#include "algorithms/evolution/data_fit.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "framework/core/error.hpp"

namespace dtsl {

DataFit data_fit(const ImplicitFunction& f, const std::vector<Vec3>& points) {
  if (points.empty()) throw AlgorithmError("data fit: no data points");
  // One distance per point, summed in point order afterwards: the mean (which decides when the
  // evolution stops) is then the same for every thread count.
  const long n = long(points.size());
  std::vector<double> distance(n);
  std::vector<char> at_critical(n, 0);
#pragma omp parallel for schedule(static)
  for (long k = 0; k < n; ++k) {
    Vec3 g;
    const double v = std::abs(f.evaluate(points[k], &g));
    const double gn = g.norm();
    distance[k] = gn > 1e-12 ? v / gn : v;
    at_critical[k] = gn > 1e-12 ? 0 : 1;
  }
  double sum = 0.0, max = 0.0;
  int critical = 0;
  for (long k = 0; k < n; ++k) {
    sum += distance[k];
    max = std::max(max, distance[k]);
    critical += at_critical[k];
  }
  return {sum / double(n), max, critical};
}

}  // namespace dtsl
