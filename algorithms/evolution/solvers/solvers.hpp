// Registration hooks of the solver plugins, one per file of this folder, and the pieces they share.
#pragma once

#include <sstream>
#include <string>

#include "algorithms/evolution/solver.hpp"
#include "framework/core/error.hpp"

namespace dtsl {

void add_eigen_ldlt_solver(Registry<LevelSetSolver>& registry);
void add_eigen_cg_solver(Registry<LevelSetSolver>& registry);
void add_ceres_solver(Registry<LevelSetSolver>& registry);
void add_cholmod_solver(Registry<LevelSetSolver>& registry);  ///< no-op without SuiteSparse

/// The common shape of a solver plugin: its options and clone().
template <class OptionsType, class Derived>
class SolverWith : public LevelSetSolver {
 public:
  Options& options() override { return options_; }
  const Options& options() const override { return options_; }
  std::unique_ptr<LevelSetSolver> clone() const override {
    auto copy = std::make_unique<Derived>();
    copy->options_ = options_;
    return copy;
  }
  OptionsType& typed_options() { return options_; }

 protected:
  OptionsType options_;
};

/// The AlgorithmError of a solver that missed its tolerance: names the solver, what happened and the
/// residual it reached.
[[noreturn]] inline void solver_failed(const std::string& solver, const std::string& what, double residual,
                                       double tolerance) {
  std::ostringstream m;
  m << solver << ": " << what << "; relative residual |A^T W (A u - b)| / |A^T W b| = " << residual
    << " (tolerance " << tolerance << ")";
  throw AlgorithmError(m.str());
}

}  // namespace dtsl
