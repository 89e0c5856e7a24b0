#include "algorithms/evolution/data_fit.hpp"

#include <algorithm>
#include <cmath>

#include "framework/core/error.hpp"

namespace dtsl {

DataFit data_fit(const ImplicitFunction& f, const std::vector<Vec3>& points) {
  if (points.empty()) throw AlgorithmError("data fit: no data points");
  double sum = 0.0, max = 0.0;
  int critical = 0;
  const long n = long(points.size());
#pragma omp parallel for schedule(static) reduction(+ : sum, critical) reduction(max : max)
  for (long k = 0; k < n; ++k) {
    Vec3 g;
    const double v = std::abs(f.evaluate(points[k], &g));
    const double gn = g.norm();
    double d = v;
    if (gn > 1e-12) d = v / gn;
    else ++critical;
    sum += d;
    max = std::max(max, d);
  }
  return {sum / double(n), max, critical};
}

}  // namespace dtsl
