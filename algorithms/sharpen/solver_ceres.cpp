// `ceres`: the same residuals as a Ceres problem, one 3-vector parameter block per sharp vertex and one
// residual block per row (Eq. 5 data rows, Eq. 7 bilateral rows), with analytic Jacobians
// (sqrt(weight) coeff_j I_3). The problem is linear, so one Levenberg-Marquardt step solves it; more are
// allowed so that a small initial trust region cannot stop it early.
#include <ceres/ceres.h>

#include <cmath>
#include <string>

#include "algorithms/sharpen/sharpen_solver.hpp"
#include "framework/core/error.hpp"

namespace dtsl::sharpen {

namespace {

struct CeresOptions final : Options {
  int max_iterations = 20;
  double function_tolerance = 1e-14;
  double gradient_tolerance = 1e-14;
  std::string linear_solver = "sparse_normal_cholesky";

  void visit(FieldVisitor& v) override {
    v.field("max_iterations", max_iterations, "Levenberg-Marquardt iteration cap");
    v.field("function_tolerance", function_tolerance, "Ceres function_tolerance");
    v.field("gradient_tolerance", gradient_tolerance, "Ceres gradient_tolerance");
    v.field("linear_solver", linear_solver, "sparse_normal_cholesky or cgnr");
  }
  void check() const override {
    check_range("max_iterations", max_iterations, 1, 1000);
    check_positive("function_tolerance", function_tolerance);
    check_positive("gradient_tolerance", gradient_tolerance);
    check_one_of("linear_solver", linear_solver, {"sparse_normal_cholesky", "cgnr"});
  }
};

class RowCost final : public ceres::CostFunction {
 public:
  explicit RowCost(const LinearRow& r) : row_(r), s_(std::sqrt(r.weight)) {
    set_num_residuals(3);
    for (int j = 0; j < r.count; ++j) mutable_parameter_block_sizes()->push_back(3);
  }
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override {
    for (int c = 0; c < 3; ++c) {
      double r = -row_.rhs[c];
      for (int j = 0; j < row_.count; ++j) r += row_.coeffs[j] * x[j][c];
      residuals[c] = s_ * r;
    }
    if (jacobians)
      for (int j = 0; j < row_.count; ++j)
        if (jacobians[j]) {
          for (int k = 0; k < 9; ++k) jacobians[j][k] = 0.0;
          for (int c = 0; c < 3; ++c) jacobians[j][4 * c] = s_ * row_.coeffs[j];
        }
    return true;
  }

 private:
  LinearRow row_;
  double s_;
};

class CeresSolver final : public SharpenSolver {
 public:
  Options& options() override { return o_; }
  Eigen::MatrixX3d solve(const LinearLeastSquares& p) override {
    o_.check();
    // Row-major storage so that each unknown's 3 coordinates are one contiguous parameter block.
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> x =
        Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>::Zero(p.unknowns, 3);
    ceres::Problem problem;
    for (int i = 0; i < p.unknowns; ++i) problem.AddParameterBlock(x.row(i).data(), 3);
    for (const auto& given : p.rows) {
      // Ceres refuses a parameter block twice in one residual: merge repeated unknowns.
      LinearRow r = given;
      r.count = 0;
      for (int j = 0; j < given.count; ++j) {
        int at = 0;
        while (at < r.count && r.unknowns[at] != given.unknowns[j]) ++at;
        if (at == r.count) {
          r.unknowns[at] = given.unknowns[j];
          r.coeffs[at] = 0.0;
          ++r.count;
        }
        r.coeffs[at] += given.coeffs[j];
      }
      if (r.count == 0) continue;
      std::vector<double*> blocks;
      for (int j = 0; j < r.count; ++j) blocks.push_back(x.row(r.unknowns[j]).data());
      problem.AddResidualBlock(new RowCost(r), nullptr, blocks);
    }
    ceres::Solver::Options so;
    so.linear_solver_type = o_.linear_solver == "cgnr" ? ceres::CGNR : ceres::SPARSE_NORMAL_CHOLESKY;
    so.max_num_iterations = o_.max_iterations;
    so.function_tolerance = o_.function_tolerance;
    so.gradient_tolerance = o_.gradient_tolerance;
    so.parameter_tolerance = 1e-14;
    so.initial_trust_region_radius = 1e8;  // linear problem: take the Gauss-Newton step at once
    so.minimizer_progress_to_stdout = false;
    so.logging_type = ceres::SILENT;
    so.num_threads = 1;
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    if (!summary.IsSolutionUsable() || !x.allFinite())
      throw AlgorithmError("sharpen solver ceres: " + summary.message);
    return Eigen::MatrixX3d(x);
  }

 private:
  CeresOptions o_;
};

}  // namespace

void add_ceres_sharpen_solver(Registry<SharpenSolver>& registry) {
  registry.add("ceres", "the same residuals as a Ceres problem (analytic Jacobians, sparse normal Cholesky)",
               [] { return std::make_unique<CeresSolver>(); });
}

}  // namespace dtsl::sharpen
