#include "algorithms/sharpen/sharpen_solver.hpp"

#include <mutex>

namespace dtsl::sharpen {

Registry<SharpenSolver>& sharpen_solvers() {
  static Registry<SharpenSolver> registry("sharpen solver");
  return registry;
}

void register_sharpen_solvers() {
  static std::once_flag once;
  std::call_once(once, [] {
    add_eigen_ldlt_sharpen_solver(sharpen_solvers());
    add_ceres_sharpen_solver(sharpen_solvers());
  });
}

double objective(const LinearLeastSquares& problem, const Eigen::MatrixX3d& x) {
  double s = 0.0;
  for (const auto& r : problem.rows) {
    Vec3 res = -r.rhs;
    for (int j = 0; j < r.count; ++j) res += r.coeffs[j] * x.row(r.unknowns[j]).transpose();
    s += r.weight * res.squaredNorm();
  }
  return s;
}

}  // namespace dtsl::sharpen
