// `cholmod` (ours, a fourth solver beside docs/design.md's three): the same normal equations as eigen_ldlt,
// formed and factorised by SuiteSparse's supernodal CHOLMOD, which does the dense-block work of the
// factor with BLAS. The normal equations of a cubic T-spline couple every control point with its 7^3 neighbours,
// so their Cholesky factor is dense in blocks and a supernodal factorisation is several times faster
// than Eigen's simplicial one (measured in bench/phase1_bench.cpp). CHOLMOD is the library Ceres
// itself uses for SPARSE_NORMAL_CHOLESKY, so it is present wherever Ceres was built with SuiteSparse;
// without it this plugin is not registered.
#include "algorithms/evolution/solvers/solvers.hpp"

#include <ceres/internal/config.h>

#if !defined(CERES_NO_SUITESPARSE) && __has_include(<suitesparse/cholmod.h>)
#define DTSL_HAVE_CHOLMOD 1
#include <suitesparse/cholmod.h>
#endif

#include <vector>

#include <cmath>
#include "framework/core/timer.hpp"

namespace dtsl {

#ifdef DTSL_HAVE_CHOLMOD
namespace {

struct CholmodOptions final : Options {
  double tolerance = 1e-8;
  std::string factorization = "supernodal";

  void visit(FieldVisitor& v) override {
    v.field("tolerance", tolerance,
            "largest relative normal-equation residual |A^T W (A u - b)| / |A^T W b| accepted");
    v.field("factorization", factorization, "'supernodal' (BLAS blocks), 'simplicial' or 'auto' (CHOLMOD decides)");
  }
  void check() const override {
    check_range("tolerance", tolerance, 1e-16, 1.0);
    check_one_of("factorization", factorization, {"supernodal", "simplicial", "auto"});
  }
};

class CholmodSolver final : public SolverWith<CholmodOptions, CholmodSolver> {
 public:
  CholmodSolver() { cholmod_start(&common_); }
  ~CholmodSolver() override {
    release_factor();
    cholmod_finish(&common_);
  }
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  SolveReport solve(const LeastSquaresSystem& system, Eigen::VectorXd& solution) override {
    Stopwatch clock;
    SolveReport report;
    report.solver = "cholmod";
    const int n = system.unknowns, m = system.rows();
    common_.supernodal = options_.factorization == "supernodal"   ? CHOLMOD_SUPERNODAL
                         : options_.factorization == "simplicial" ? CHOLMOD_SIMPLICIAL
                                                                  : CHOLMOD_AUTO;
    common_.print = 0;
    // CHOLMOD factorises A^T W A straight from the rows: given the unsymmetric n x m matrix
    // G = (sqrt(W) A)^T it computes L L^T = G G^T itself (as Ceres' SPARSE_NORMAL_CHOLESKY does). The
    // rows of A in compressed-row form are the columns of A^T in compressed-column form, so only the
    // values are scaled and copied.
    scaled_.resize(system.value.size());
    rhs_ = Eigen::VectorXd::Zero(n);
    for (int r = 0; r < m; ++r) {
      const double root = std::sqrt(system.weight[r]);
      for (int e = system.row_begin[r]; e < system.row_begin[r + 1]; ++e) {
        scaled_[e] = root * system.value[e];
        rhs_[system.column[e]] += system.weight[r] * system.value[e] * system.rhs[r];
      }
    }
    cholmod_sparse G{};
    G.nrow = std::size_t(n);
    G.ncol = std::size_t(m);
    G.nzmax = system.value.size();
    G.p = const_cast<int*>(system.row_begin.data());
    G.i = const_cast<int*>(system.column.data());
    G.x = scaled_.data();
    G.stype = 0;
    G.itype = CHOLMOD_INT;
    G.xtype = CHOLMOD_REAL;
    G.dtype = CHOLMOD_DOUBLE;
    G.sorted = 0;
    G.packed = 1;

    const bool same_pattern = factor_ && same_pattern_as_last(system);
    if (!same_pattern) {
      release_factor();
      remember_pattern(system);
      factor_ = cholmod_analyze(&G, &common_);
      if (!factor_) solver_failed("cholmod", "analysis failed", std::numeric_limits<double>::infinity(), options_.tolerance);
    }
    if (!cholmod_factorize(&G, factor_, &common_) || common_.status != CHOLMOD_OK) {
      release_factor();
      solver_failed("cholmod", "factorisation failed (normal equations not positive definite?)",
                    std::numeric_limits<double>::infinity(), options_.tolerance);
    }
    cholmod_dense b{};
    b.nrow = std::size_t(n);
    b.ncol = 1;
    b.nzmax = std::size_t(n);
    b.d = std::size_t(n);
    b.x = rhs_.data();
    b.xtype = CHOLMOD_REAL;
    b.dtype = CHOLMOD_DOUBLE;
    cholmod_dense* x = cholmod_solve(CHOLMOD_A, factor_, &b, &common_);
    if (!x) solver_failed("cholmod", "solve failed", std::numeric_limits<double>::infinity(), options_.tolerance);
    solution = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(x->x), n);
    cholmod_free_dense(&x, &common_);

    report.iterations = 1;
    report.relative_residual = system.relative_residual(solution);
    report.seconds = clock.seconds();
    report.details = {{"reused_analysis", same_pattern},
                      {"supernodal", factor_->is_super != 0},
                      {"factor_nonzeros", double(common_.lnz)}};
    if (!solution.allFinite() || !(report.relative_residual <= options_.tolerance))
      solver_failed("cholmod", "solution misses the tolerance", report.relative_residual, options_.tolerance);
    return report;
  }

 private:
  void release_factor() {
    if (factor_) cholmod_free_factor(&factor_, &common_);
    factor_ = nullptr;
  }
  void remember_pattern(const LeastSquaresSystem& s) {
    pattern_outer_ = s.row_begin;
    pattern_inner_ = s.column;
    pattern_unknowns_ = s.unknowns;
  }
  bool same_pattern_as_last(const LeastSquaresSystem& s) const {
    return pattern_unknowns_ == s.unknowns && pattern_outer_ == s.row_begin && pattern_inner_ == s.column;
  }

  cholmod_common common_{};
  cholmod_factor* factor_ = nullptr;
  std::vector<int> pattern_outer_, pattern_inner_;
  int pattern_unknowns_ = -1;
  std::vector<double> scaled_;
  Eigen::VectorXd rhs_;
};

}  // namespace
#endif

bool cholmod_available() {
#ifdef DTSL_HAVE_CHOLMOD
  return true;
#else
  return false;
#endif
}

void add_cholmod_solver(Registry<LevelSetSolver>& registry) {
#ifdef DTSL_HAVE_CHOLMOD
  registry.add("cholmod", "supernodal sparse Cholesky (SuiteSparse CHOLMOD) of the normal equations",
               [] { return std::make_unique<CholmodSolver>(); });
#else
  (void)registry;
#endif
}

}  // namespace dtsl
