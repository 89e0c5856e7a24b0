// `ceres`: the same weighted rows as a Ceres problem (docs/design.md §1, "the same residuals as a Ceres
// problem"): one parameter block per unknown coefficient, one residual block per row,
// residual_r = sqrt(w_r) (a_r . u - b_r). The problem is linear, so the trust-region solver is run
// with a huge initial radius (Levenberg–Marquardt damping 1e-16): its first step is the Gauss–Newton
// step, i.e. the exact minimiser up to the linear solver's accuracy, and the next iteration confirms
// convergence. Linear solvers: SPARSE_NORMAL_CHOLESKY (SuiteSparse's supernodal CHOLMOD, or Eigen's
// sparse Cholesky) or CGNR (conjugate gradients on the normal equations, inside Ceres).
//
// The distance-field residual is kept in its linearised form, so all three solvers minimise one
// objective and must agree (tested).
#include <ceres/ceres.h>

#include <cmath>
#include <thread>

#include "algorithms/evolution/solvers/solvers.hpp"
#include "framework/core/timer.hpp"

namespace dtsl {

namespace {

struct CeresSolverOptions final : Options {
  std::string linear_solver = "sparse_normal_cholesky";
  std::string sparse_library = "suite_sparse";
  double tolerance = 1e-6;
  int max_iterations = 10;
  int threads = 0;
  bool dynamic_sparsity = true;

  void visit(FieldVisitor& v) override {
    v.field("linear_solver", linear_solver, "'sparse_normal_cholesky' or 'cgnr'");
    v.field("sparse_library", sparse_library,
            "'suite_sparse' (CHOLMOD) or 'eigen_sparse', for sparse_normal_cholesky");
    v.field("tolerance", tolerance,
            "largest relative normal-equation residual |A^T W (A u - b)| / |A^T W b| accepted (CGNR also "
            "uses it as its own tolerance)");
    v.field("max_iterations", max_iterations, "Ceres trust-region iteration cap (a linear problem needs 1-2)");
    v.field("threads", threads, "Ceres threads; 0 = the hardware concurrency");
    v.field("dynamic_sparsity", dynamic_sparsity,
            "Ceres' dynamic-sparsity path for sparse_normal_cholesky (the factorisation works on the "
            "Jacobian directly; measured ~10x faster here than the block-sparse J^T J of 1x1 blocks)");
  }
  void check() const override {
    check_one_of("linear_solver", linear_solver, {"sparse_normal_cholesky", "cgnr"});
    check_one_of("sparse_library", sparse_library, {"suite_sparse", "eigen_sparse"});
    check_range("tolerance", tolerance, 1e-16, 1.0);
    check_range("max_iterations", max_iterations, 1, 10000);
    check_range("threads", threads, 0, 1024);
  }
};

/// One row: sqrt(w) (sum_e a_e u_{c_e} - b), each u a parameter block of size 1.
class RowCost final : public ceres::CostFunction {
 public:
  RowCost(const double* a, int count, double b, double sqrt_w) : a_(a), b_(b), sqrt_w_(sqrt_w) {
    set_num_residuals(1);
    mutable_parameter_block_sizes()->assign(count, 1);
  }
  bool Evaluate(double const* const* u, double* residual, double** jacobians) const override {
    const int k = int(parameter_block_sizes().size());
    double sum = -b_;
    for (int e = 0; e < k; ++e) sum += a_[e] * u[e][0];
    residual[0] = sqrt_w_ * sum;
    if (jacobians)
      for (int e = 0; e < k; ++e)
        if (jacobians[e]) jacobians[e][0] = sqrt_w_ * a_[e];
    return true;
  }

 private:
  const double* a_;
  double b_, sqrt_w_;
};

class CeresSolver final : public SolverWith<CeresSolverOptions, CeresSolver> {
 public:
  SolveReport solve(const LeastSquaresSystem& system, Eigen::VectorXd& solution) override {
    Stopwatch clock;
    SolveReport report;
    report.solver = "ceres";
    if (solution.size() != system.unknowns || !solution.allFinite()) solution = Eigen::VectorXd::Zero(system.unknowns);

    ceres::Problem::Options problem_options;
    problem_options.enable_fast_removal = false;
    ceres::Problem problem(problem_options);
    for (int k = 0; k < system.unknowns; ++k) problem.AddParameterBlock(solution.data() + k, 1);
    std::vector<double*> blocks;
    for (int r = 0; r < system.rows(); ++r) {
      const int begin = system.row_begin[r], count = system.row_begin[r + 1] - begin;
      if (count == 0 || system.weight[r] == 0.0) continue;
      blocks.clear();
      for (int e = begin; e < begin + count; ++e) blocks.push_back(solution.data() + system.column[e]);
      problem.AddResidualBlock(new RowCost(system.value.data() + begin, count, system.rhs[r], std::sqrt(system.weight[r])),
                               nullptr, blocks);
    }
    const double build = clock.seconds();

    ceres::Solver::Options o;
    o.linear_solver_type = options_.linear_solver == "cgnr" ? ceres::CGNR : ceres::SPARSE_NORMAL_CHOLESKY;
    o.sparse_linear_algebra_library_type =
        options_.sparse_library == "eigen_sparse" ? ceres::EIGEN_SPARSE : ceres::SUITE_SPARSE;
    o.dynamic_sparsity = options_.dynamic_sparsity;
    o.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
    o.initial_trust_region_radius = 1e16;  // LM damping 1e-16: the first step is Gauss-Newton
    o.max_trust_region_radius = 1e32;
    o.max_num_iterations = options_.max_iterations;
    o.function_tolerance = 1e-14;
    o.gradient_tolerance = 1e-14;
    o.parameter_tolerance = 1e-14;
    o.min_linear_solver_iterations = 1;
    o.max_linear_solver_iterations = 2000;
    o.eta = std::min(options_.tolerance, 0.1);
    o.num_threads = options_.threads > 0 ? options_.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    o.logging_type = ceres::SILENT;
    o.minimizer_progress_to_stdout = false;
    ceres::Solver::Summary summary;
    ceres::Solve(o, &problem, &summary);

    report.iterations = int(summary.iterations.size()) - 1;  // iteration 0 is the starting point
    report.relative_residual = system.relative_residual(solution);
    report.seconds = clock.seconds();
    report.details = {{"build_seconds", build},
                      {"termination", ceres::TerminationTypeToString(summary.termination_type)},
                      {"initial_cost", summary.initial_cost},
                      {"final_cost", summary.final_cost},
                      {"linear_solver", options_.linear_solver},
                      {"preprocessor_seconds", summary.preprocessor_time_in_seconds},
                      {"jacobian_seconds", summary.jacobian_evaluation_time_in_seconds},
                      {"linear_solver_seconds", summary.linear_solver_time_in_seconds},
                      {"minimizer_seconds", summary.minimizer_time_in_seconds}};
    if (!summary.IsSolutionUsable() || !solution.allFinite())
      solver_failed("ceres", "solve failed (" + summary.message + ")", report.relative_residual, options_.tolerance);
    if (!(report.relative_residual <= options_.tolerance))
      solver_failed("ceres", "solution misses the tolerance (" + summary.message + ")", report.relative_residual,
                    options_.tolerance);
    return report;
  }
};

}  // namespace

void add_ceres_solver(Registry<LevelSetSolver>& registry) {
  registry.add("ceres", "the rows as a Ceres problem (sparse normal Cholesky or CGNR); linear, solved by one Gauss-Newton step",
               [] { return std::make_unique<CeresSolver>(); });
}

}  // namespace dtsl
