// The linear least-squares problem of one bilateral-evolution step (paper Eq. 4-7) and its solver plugins.
//
// Every residual of Eq. 5 (q_k + sum_j lambda_j v'_j - p_k) and Eq. 7 (v_i + v'_i - v'_i target) is a
// 3-vector whose coefficients on the unknown velocities are scalars times the identity. The three
// coordinates therefore decouple: one sparse matrix A (rows x sharp vertices) serves x, y and z, with
// three right-hand sides. `eigen_ldlt` factors A^T W A once (SimplicialLDLT) and solves all three;
// `ceres` states the same residuals as a Ceres problem (3-vector parameter blocks) and lets Ceres solve it.
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "framework/config/options.hpp"
#include "framework/core/types.hpp"
#include "framework/registry/registry.hpp"

namespace dtsl::sharpen {

/// weight * |sum_{j < count} coeff_j x_{unknown_j} - rhs|^2, x_j in R^3.
struct LinearRow {
  int count = 0;
  std::array<int, 3> unknowns{};
  std::array<double, 3> coeffs{};
  Vec3 rhs = Vec3::Zero();
  double weight = 1.0;
};

struct LinearLeastSquares {
  int unknowns = 0;  ///< number of 3-vector unknowns
  std::vector<LinearRow> rows;
};

class SharpenSolver {
 public:
  virtual ~SharpenSolver() = default;
  virtual Options& options() = 0;
  /// The minimiser, one row per unknown. Throws AlgorithmError if the problem is singular or the
  /// solver fails, naming the solver.
  virtual Eigen::MatrixX3d solve(const LinearLeastSquares& problem) = 0;
};

Registry<SharpenSolver>& sharpen_solvers();
/// Adds eigen_ldlt and ceres. Idempotent.
void register_sharpen_solvers();

/// sum_rows weight * |residual|^2 at x (for tests and diagnostics).
double objective(const LinearLeastSquares& problem, const Eigen::MatrixX3d& x);

// Registration hooks, one per solver file.
void add_eigen_ldlt_sharpen_solver(Registry<SharpenSolver>& registry);
void add_ceres_sharpen_solver(Registry<SharpenSolver>& registry);

}  // namespace dtsl::sharpen
