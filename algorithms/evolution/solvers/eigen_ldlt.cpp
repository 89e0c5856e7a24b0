// `eigen_ldlt`: the normal equations A^T W A u = A^T W b factorised by Eigen's SimplicialLDLT with an
// AMD ordering (docs/design.md §1, "direct sparse Cholesky on the normal equations"). The symbolic analysis
// is kept and reused while the sparsity pattern stays the same (it usually changes with the zero set,
// so this only helps repeated solves on one set of rows, e.g. the final refinement's Gauss-Newton steps
// when the band does not move).
#include <Eigen/SparseCholesky>
#include <vector>

#include "algorithms/evolution/normal_equations.hpp"
#include "algorithms/evolution/solvers/solvers.hpp"
#include "framework/core/timer.hpp"

namespace dtsl {

namespace {

struct EigenLdltOptions final : Options {
  double tolerance = 1e-8;

  void visit(FieldVisitor& v) override {
    v.field("tolerance", tolerance,
            "largest relative normal-equation residual |A^T W (A u - b)| / |A^T W b| accepted; above it "
            "(a numerically singular system) the solve fails with an AlgorithmError");
  }
  void check() const override { check_range("tolerance", tolerance, 1e-16, 1.0); }
};

class EigenLdltSolver final : public SolverWith<EigenLdltOptions, EigenLdltSolver> {
 public:
  SolveReport solve(const LeastSquaresSystem& system, Eigen::VectorXd& solution) override {
    Stopwatch clock;
    SolveReport report;
    report.solver = "eigen_ldlt";
    const NormalEquations normal = normal_equations(system);
    const double assemble = clock.seconds();
    const bool same_pattern = same_pattern_as_last(normal.lower);
    if (!same_pattern) ldlt_.analyzePattern(normal.lower);
    ldlt_.factorize(normal.lower);
    if (ldlt_.info() != Eigen::Success) {
      pattern_outer_.clear();
      solver_failed("eigen_ldlt", "factorisation failed (normal equations not positive definite)",
                    std::numeric_limits<double>::infinity(), options_.tolerance);
    }
    solution = ldlt_.solve(normal.rhs);
    report.iterations = 1;
    report.relative_residual = system.relative_residual(solution);
    report.seconds = clock.seconds();
    report.details = {{"assemble_seconds", assemble},
                      {"nonzeros", normal.lower.nonZeros()},
                      {"reused_analysis", same_pattern},
                      {"factor_nonzeros", ldlt_.matrixL().nestedExpression().nonZeros()}};
    if (!solution.allFinite() || !(report.relative_residual <= options_.tolerance))
      solver_failed("eigen_ldlt", "solution misses the tolerance", report.relative_residual, options_.tolerance);
    return report;
  }

 private:
  bool same_pattern_as_last(const Eigen::SparseMatrix<double>& m) {
    const int n = int(m.cols());
    const bool same = int(pattern_outer_.size()) == n + 1 && int(pattern_inner_.size()) == m.nonZeros() &&
                      std::equal(pattern_outer_.begin(), pattern_outer_.end(), m.outerIndexPtr()) &&
                      std::equal(pattern_inner_.begin(), pattern_inner_.end(), m.innerIndexPtr());
    if (!same) {
      pattern_outer_.assign(m.outerIndexPtr(), m.outerIndexPtr() + n + 1);
      pattern_inner_.assign(m.innerIndexPtr(), m.innerIndexPtr() + m.nonZeros());
    }
    return same;
  }

  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt_;
  std::vector<int> pattern_outer_, pattern_inner_;
};

}  // namespace

void add_eigen_ldlt_solver(Registry<LevelSetSolver>& registry) {
  registry.add("eigen_ldlt", "sparse LDLT (Eigen SimplicialLDLT, AMD) of the normal equations",
               [] { return std::make_unique<EigenLdltSolver>(); });
}

}  // namespace dtsl
