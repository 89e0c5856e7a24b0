// Solvers of the level-set stage's least-squares problems (docs/design.md §1: "Solvers (plugins):
// eigen_ldlt (direct sparse Cholesky on the normal equations), eigen_cg (conjugate gradients
// warm-started from the last c'), and ceres (the same residuals as a Ceres problem)").
//
// Every solver takes the same LeastSquaresSystem and returns its minimiser; they agree to their
// tolerances (tested). A solver that cannot reach its tolerance throws AlgorithmError naming itself
// and the relative residual |A^T W (A u - b)| / |A^T W b| it got — unless its options name a
// fallback (eigen_cg: `on_failure: eigen_ldlt`), which the report then records.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "algorithms/evolution/least_squares_rows.hpp"
#include "framework/config/options.hpp"
#include "framework/registry/registry.hpp"

namespace dtsl {

struct SolveReport {
  std::string solver;          ///< the plugin that produced the solution (a fallback's name if one was used)
  int iterations = 0;          ///< CG iterations / Ceres iterations; 1 for a direct factorisation
  double relative_residual = 0.0;  ///< |A^T W (A u - b)| / |A^T W b| of the returned solution
  double seconds = 0.0;
  bool fell_back = false;      ///< the plugin missed its tolerance and used its documented fallback
  nlohmann::json details = nlohmann::json::object();  ///< solver-specific (factorisation reuse, ...)
};
nlohmann::json to_json(const SolveReport& r);

class LevelSetSolver {
 public:
  virtual ~LevelSetSolver() = default;
  virtual Options& options() = 0;
  virtual const Options& options() const = 0;
  /// A fresh solver with the same options (no cached factorisation).
  virtual std::unique_ptr<LevelSetSolver> clone() const = 0;
  /// Minimises the system. `solution` holds the warm start on entry (the previous step's c',
  /// restricted to this system's unknowns; solvers that cannot use it ignore it) and the minimiser on
  /// return. Not thread-safe: a solver may cache work between calls (a symbolic factorisation).
  virtual SolveReport solve(const LeastSquaresSystem& system, Eigen::VectorXd& solution) = 0;
};

Registry<LevelSetSolver>& level_set_solvers();

/// Whether the `cholmod` plugin was built (SuiteSparse found through Ceres).
bool cholmod_available();

/// Adds `eigen_ldlt`, `eigen_cg`, `ceres` and (where SuiteSparse is available) `cholmod` to
/// level_set_solvers(). Idempotent.
void register_level_set_solvers();

}  // namespace dtsl
