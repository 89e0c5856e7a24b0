// The solver plugins agree on the same step; failures are AlgorithmErrors naming the solver and the
// residual, or the documented fallback.
#include <catch2/catch.hpp>

#include "algorithms/evolution/solver.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "tests/evolution/fixtures.hpp"

using namespace dtsl;

namespace {

std::unique_ptr<LevelSetSolver> make(const std::string& name) {
  register_level_set_solvers();
  return level_set_solvers().create(name, "test");
}

const LeastSquaresSystem& torus_step() {
  static const LeastSquaresSystem s = test::step_system(test::torus_data(), test::test_options("distance", "eigen_ldlt"));
  return s;
}

}  // namespace

TEST_CASE("solvers: eigen_ldlt, eigen_cg and ceres are registered (cholmod with SuiteSparse)", "[evolution][solver]") {
  register_level_set_solvers();
  for (const char* name : {"eigen_ldlt", "eigen_cg", "ceres"}) CHECK(level_set_solvers().contains(name));
  CHECK(level_set_solvers().contains("cholmod") == cholmod_available());
  for (const std::string& name : level_set_solvers().names()) {
    INFO(name);
    auto s = make(name);
    CHECK_NOTHROW(s->options().check());
    for (const auto& field : describe(s->options())) CHECK(!field.doc.empty());
  }
}

TEST_CASE("solvers agree on one evolution step", "[evolution][solver]") {
  const LeastSquaresSystem& system = torus_step();
  REQUIRE(system.unknowns > 100);
  auto ldlt = make("eigen_ldlt");
  Eigen::VectorXd reference = Eigen::VectorXd::Zero(system.unknowns);
  const SolveReport r = ldlt->solve(system, reference);
  CHECK(r.relative_residual < 1e-8);
  CHECK(reference.norm() > 0.0);
  for (const std::string& name : level_set_solvers().names()) {
    INFO(name);
    auto solver = make(name);
    if (name == "eigen_cg") apply_assignment(solver->options(), "tolerance", "1e-10", "solver");
    if (name == "ceres") apply_assignment(solver->options(), "tolerance", "1e-8", "solver");
    Eigen::VectorXd u = Eigen::VectorXd::Zero(system.unknowns);
    const SolveReport report = solver->solve(system, u);
    INFO(to_json(report).dump());
    CHECK(report.relative_residual < 1e-6);
    CHECK(!report.fell_back);
    // The normal equations are SPD: equal residuals mean equal solutions, up to the conditioning.
    CHECK((u - reference).norm() <= 1e-4 * reference.norm());
    CHECK(system.objective(u) == Approx(system.objective(reference)).epsilon(1e-8));
  }
  // A second solve on the same rows reuses the symbolic analysis and gives the same answer.
  Eigen::VectorXd again = Eigen::VectorXd::Zero(system.unknowns);
  const SolveReport second = ldlt->solve(system, again);
  CHECK(second.details["reused_analysis"].get<bool>());
  CHECK((again - reference).norm() <= 1e-12 * reference.norm());
}

TEST_CASE("eigen_cg: warm start from the solution converges at once", "[evolution][solver]") {
  const LeastSquaresSystem& system = torus_step();
  auto cg = make("eigen_cg");
  Eigen::VectorXd cold = Eigen::VectorXd::Zero(system.unknowns);
  const SolveReport first = cg->solve(system, cold);
  Eigen::VectorXd warm = cold;
  const SolveReport second = cg->solve(system, warm);
  CHECK(second.iterations < std::max(2, first.iterations / 10));
}

TEST_CASE("solvers: a solve that misses its tolerance names the solver and the residual", "[evolution][solver][bad]") {
  const LeastSquaresSystem& system = torus_step();
  SECTION("eigen_cg with on_failure = error") {
    auto cg = make("eigen_cg");
    apply_assignment(cg->options(), "max_iterations", "2", "solver");
    apply_assignment(cg->options(), "tolerance", "1e-12", "solver");
    apply_assignment(cg->options(), "on_failure", "error", "solver");
    Eigen::VectorXd u = Eigen::VectorXd::Zero(system.unknowns);
    try {
      cg->solve(system, u);
      FAIL("no error");
    } catch (const AlgorithmError& e) {
      const std::string m = e.what();
      CHECK(m.find("eigen_cg") != std::string::npos);
      CHECK(m.find("relative residual") != std::string::npos);
    }
  }
  SECTION("eigen_cg with the documented fallback to eigen_ldlt") {
    auto cg = make("eigen_cg");
    apply_assignment(cg->options(), "max_iterations", "2", "solver");
    apply_assignment(cg->options(), "tolerance", "1e-12", "solver");
    apply_assignment(cg->options(), "on_failure", "eigen_ldlt", "solver");
    Eigen::VectorXd u = Eigen::VectorXd::Zero(system.unknowns);
    const SolveReport report = cg->solve(system, u);
    CHECK(report.fell_back);
    CHECK(report.solver == "eigen_ldlt");
    CHECK(report.details["cg_iterations"].get<int>() == 2);
    CHECK(report.relative_residual < 1e-8);
  }
  SECTION("a singular system: no smoothness and an unknown no row constrains") {
    LeastSquaresSystem singular = system;
    // Zero the columns of unknown 0 in every row: nothing determines it, and w_S = 0.
    singular.row_begin.resize(singular.value_rows + singular.gradient_rows + 1);
    singular.rhs.resize(singular.row_begin.size() - 1);
    singular.weight.resize(singular.rhs.size());
    singular.column.resize(singular.row_begin.back());
    singular.value.resize(singular.row_begin.back());
    singular.smoothness_rows = 0;
    for (std::size_t e = 0; e < singular.column.size(); ++e)
      if (singular.column[e] == 0) singular.value[e] = 0.0;
    for (const std::string& name : {std::string("eigen_ldlt"), std::string("ceres")}) {
      INFO(name);
      Eigen::VectorXd u = Eigen::VectorXd::Zero(singular.unknowns);
      try {
        make(name)->solve(singular, u);
        // Accepted only if the answer really solves the normal equations (a minimum-norm-like answer).
        CHECK(singular.relative_residual(u) < 1e-6);
      } catch (const AlgorithmError& e) {
        CHECK(std::string(e.what()).find(name) != std::string::npos);
      }
    }
  }
}
