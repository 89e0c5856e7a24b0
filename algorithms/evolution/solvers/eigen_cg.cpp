// `eigen_cg`: conjugate gradients on the normal equations, warm-started from the caller's guess (the
// evolution passes the previous step's c', docs/design.md §1), Jacobi-preconditioned (an incomplete
// Cholesky preconditioner made the level-set stage 1.3-2.6x slower and was removed), with the products
// taken on the stored lower triangle (conjugate_gradient.hpp). CG that misses its
// tolerance within max_iterations either falls back, documented and tested, to the direct eigen_ldlt
// factorisation of the same normal equations (on_failure = eigen_ldlt, the default; the report says
// fell_back, solver = "eigen_ldlt"), or throws (on_failure = error: an AlgorithmError naming eigen_cg
// and the residual).
#include <Eigen/SparseCholesky>
#include <string>

#include "algorithms/evolution/conjugate_gradient.hpp"
#include "algorithms/evolution/normal_equations.hpp"
#include "algorithms/evolution/solvers/solvers.hpp"
#include "framework/core/timer.hpp"

namespace dtsl {

namespace {

struct EigenCgOptions final : Options {
  // Looser solves are cheaper (a warm-started CG reaches 1e-3 in ~70 iterations where 1e-6 takes
  // 130-1400) but unstable at scale: on 100k armadillo points 1e-3 and 1e-4 let errors in weakly
  // determined coefficients grow step by step into hundreds of spurious handles, 1e-5 evolves as 1e-6
  // does at half the solve time (measured at 100k points). At 1e-5 and 2e-5 the sphere start with
  // `geodesic` leaves a membrane in the hole of tests/evolution's torus; at 5e-6 and tighter it opens, at
  // a cost of 8 % more iterations on the dev half's hand (docs/performance.md, "What keeps it fast").
  double tolerance = 5e-6;
  int max_iterations = 2000;
  std::string on_failure = "eigen_ldlt";

  void visit(FieldVisitor& v) override {
    v.field("tolerance", tolerance,
            "stop when the relative residual |N u - g| / |g| of the normal equations is below this");
    v.field("max_iterations", max_iterations, "CG iteration cap");
    v.field("on_failure", on_failure,
            "when CG misses the tolerance: 'error' (AlgorithmError naming the residual) or 'eigen_ldlt' "
            "(solve the same normal equations directly; the report says so)");
  }
  void check() const override {
    check_range("tolerance", tolerance, 1e-16, 1.0);
    check_range("max_iterations", max_iterations, 1, 1000000);
    check_one_of("on_failure", on_failure, {"error", "eigen_ldlt"});
  }
};

class EigenCgSolver final : public SolverWith<EigenCgOptions, EigenCgSolver> {
 public:
  SolveReport solve(const LeastSquaresSystem& system, Eigen::VectorXd& solution) override {
    Stopwatch clock;
    SolveReport report;
    report.solver = "eigen_cg";
    const NormalEquations normal = normal_equations(system);
    const double forming_seconds = clock.seconds();  // where the time goes: forming vs iterating
    if (solution.size() != system.unknowns || !solution.allFinite()) solution = Eigen::VectorXd::Zero(system.unknowns);
    // One parallel region per product: runs side by side must not oversubscribe the cores (`dtsl run
    // --jobs`), or every product's barrier waits for a descheduled thread.
    const ConjugateGradientResult cg =
        jacobi_conjugate_gradient(normal.lower, normal.rhs, options_.tolerance, options_.max_iterations, solution);
    report.iterations = cg.iterations;
    const double cg_error = cg.relative_residual;
    const bool converged = cg.converged && solution.allFinite();
    report.relative_residual = system.relative_residual(solution);
    report.details = {{"cg_error", cg_error}, {"normal_equations_seconds", forming_seconds}};
    if (!converged) {
      if (options_.on_failure == "error")
        solver_failed("eigen_cg", "no convergence in " + std::to_string(report.iterations) + " iterations",
                      report.relative_residual, options_.tolerance);
      // Documented fallback: the direct factorisation of the same normal equations.
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt(normal.lower);
      if (ldlt.info() != Eigen::Success)
        solver_failed("eigen_cg", "no convergence, and the eigen_ldlt fallback could not factorise",
                      report.relative_residual, options_.tolerance);
      report.details["cg_iterations"] = report.iterations;
      report.details["cg_relative_residual"] = report.relative_residual;
      solution = ldlt.solve(normal.rhs);
      report.relative_residual = system.relative_residual(solution);
      report.solver = "eigen_ldlt";
      report.fell_back = true;
    }
    report.seconds = clock.seconds();
    return report;
  }
};

}  // namespace

void add_eigen_cg_solver(Registry<LevelSetSolver>& registry) {
  registry.add("eigen_cg", "conjugate gradients on the normal equations, warm-started from the last step",
               [] { return std::make_unique<EigenCgSolver>(); });
}

}  // namespace dtsl
