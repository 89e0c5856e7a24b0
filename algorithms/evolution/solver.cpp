#include "algorithms/evolution/solver.hpp"

#include "algorithms/evolution/solvers/solvers.hpp"

namespace dtsl {

nlohmann::json to_json(const SolveReport& r) {
  nlohmann::json j = {{"solver", r.solver},
                      {"iterations", r.iterations},
                      {"relative_residual", r.relative_residual},
                      {"seconds", r.seconds},
                      {"fell_back", r.fell_back}};
  if (!r.details.empty()) j["details"] = r.details;
  return j;
}

Registry<LevelSetSolver>& level_set_solvers() {
  static Registry<LevelSetSolver> registry("level-set solver");
  return registry;
}

void register_level_set_solvers() {
  static bool done = false;
  if (done) return;
  done = true;
  add_eigen_ldlt_solver(level_set_solvers());
  add_eigen_cg_solver(level_set_solvers());
  add_ceres_solver(level_set_solvers());
  add_cholmod_solver(level_set_solvers());
}

}  // namespace dtsl
