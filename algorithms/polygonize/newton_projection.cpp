#include "algorithms/polygonize/newton_projection.hpp"

#include <cmath>
#include <cstddef>

#include "framework/config/options.hpp"

namespace dtsl {

void NewtonOptions::check(const std::string& prefix) const {
  check_range((prefix + "tolerance").c_str(), tolerance, 1e-15, 1e-2);
  check_range((prefix + "max_iterations").c_str(), max_iterations, 1, 10000);
  check_positive((prefix + "max_step").c_str(), max_step);
  check_non_negative((prefix + "min_gradient").c_str(), min_gradient);
}

const char* to_string(NewtonStatus status) {
  switch (status) {
    case NewtonStatus::converged: return "converged";
    case NewtonStatus::max_iterations: return "max_iterations";
    case NewtonStatus::zero_gradient: return "zero_gradient";
    case NewtonStatus::not_finite: return "not_finite";
  }
  return "unknown";
}

NewtonProjection newton_project(const ImplicitFunction& f, const Vec3& start, const NewtonOptions& options) {
  NewtonProjection r;
  r.point = start;
  for (int it = 0;; ++it) {
    r.value = f.evaluate(r.point, &r.gradient);
    r.iterations = it;
    if (!std::isfinite(r.value) || !r.gradient.allFinite()) {
      r.status = NewtonStatus::not_finite;
      return r;
    }
    const double g2 = r.gradient.squaredNorm();
    if (g2 <= options.min_gradient * options.min_gradient || g2 == 0.0) {
      r.status = NewtonStatus::zero_gradient;
      return r;
    }
    // The convergence test looks at the step that would come next, so the returned point (and the
    // gradient evaluated there) already satisfies the tolerance: no extra evaluation is wasted.
    const double length = std::abs(r.value) / std::sqrt(g2);
    if (length < options.tolerance) {
      r.status = NewtonStatus::converged;
      return r;
    }
    if (it >= options.max_iterations) {
      r.status = NewtonStatus::max_iterations;
      return r;
    }
    Vec3 step = (r.value / g2) * r.gradient;
    if (length > options.max_step) step *= options.max_step / length;
    r.point -= step;
  }
}

std::vector<NewtonProjection> newton_project_all(const ImplicitFunction& f, const std::vector<Vec3>& points,
                                                 const NewtonOptions& options) {
  std::vector<NewtonProjection> out(points.size());
  const long n = static_cast<long>(points.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (long i = 0; i < n; ++i) out[static_cast<std::size_t>(i)] = newton_project(f, points[static_cast<std::size_t>(i)], options);
  return out;
}

}  // namespace dtsl
