// Bad input to the level-set stage: a clear error or a documented, tested result — never a
// hang or a crash.
#include <catch2/catch.hpp>

#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "tests/evolution/fixtures.hpp"

using namespace dtsl;

namespace {

template <class E>
std::string error_of(const std::vector<Vec3>& points, const EvolutionOptions& o) {
  try {
    compute_level_set(points, o);
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("bad input: fewer than 4 points, coinciding or non-finite points are AlgorithmErrors", "[evolution][bad]") {
  const EvolutionOptions o = test::test_options("distance_balloon", "eigen_cg");
  CHECK(!error_of<AlgorithmError>({}, o).empty());
  CHECK(!error_of<AlgorithmError>({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, o).empty());
  CHECK(!error_of<AlgorithmError>(std::vector<Vec3>(50, Vec3(0.2, 0.1, -0.3)), o).empty());
  std::vector<Vec3> nan_point = test::sphere_data(100);
  nan_point[7].x() = std::numeric_limits<double>::quiet_NaN();
  CHECK(!error_of<AlgorithmError>(nan_point, o).empty());
  // Points outside the T-mesh's domain (not normalised into [-1,1]^3).
  std::vector<Vec3> far = test::sphere_data(100);
  for (Vec3& p : far) p *= 5.0;
  CHECK(!error_of<AlgorithmError>(far, o).empty());
}

TEST_CASE("bad input: options out of range are ConfigErrors naming the field", "[evolution][bad]") {
  const std::vector<Vec3> points = test::sphere_data(200);
  for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{
           {"tmesh_max_depth", "11"}, {"tmesh_max_depth", "0"}, {"cfl", "0"}, {"w_distance", "-1"},
           {"velocity_beta", "2"}, {"solver_tolerance", "0"}, {"refine_target_level", "12"},
           {"initial_box_margin", "0.5"}}) {
    INFO(key << " = " << value);
    EvolutionOptions o = test::test_options("distance_balloon", "eigen_cg");
    try {
      apply_assignment(o, key, value, "level_set");  // runs check()
      FAIL("accepted");
    } catch (const ConfigError& e) {
      CHECK(std::string(e.what()).find(key) != std::string::npos);
    }
  }
  EvolutionOptions o = test::test_options("distance_balloon", "eigen_cg");
  o.tmesh.max_depth = 11;  // set directly: compute_level_set checks too
  const std::string m = error_of<ConfigError>(points, o);
  CHECK(m.find("tmesh_max_depth") != std::string::npos);
  o = test::test_options("no_such_velocity", "eigen_cg");
  CHECK(error_of<ConfigError>(points, o).find("no_such_velocity") != std::string::npos);
  o = test::test_options("distance", "no_such_solver");
  CHECK(error_of<ConfigError>(points, o).find("known:") != std::string::npos);
}

TEST_CASE("bad input: points on a plane or a line end in a documented result, not a hang", "[evolution][bad]") {
  // Data with no volume: the inside region shrinks onto the data and, with nothing to enclose,
  // vanishes. The evolution stops ("level set vanished") or stalls, within the iteration cap, and keeps
  // the iterate closest to the data; the result is a valid level set (possibly with no zero set).
  std::vector<Vec3> plane, line;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 30; ++j) plane.emplace_back(-0.9 + 1.8 * i / 29.0, -0.9 + 1.8 * j / 29.0, 0.0);
  for (int i = 0; i < 400; ++i) line.emplace_back(-1.0 + 2.0 * i / 399.0, 0.0, 0.0);
  for (const auto* name : {"plane", "line"}) {
    DYNAMIC_SECTION(name) {
      const std::vector<Vec3>& points = std::string(name) == "plane" ? plane : line;
      EvolutionOptions o = test::test_options("distance_balloon", "eigen_cg");
      o.max_iterations = 60;
      const LevelSetResult r = compute_level_set(points, o);
      INFO("stop: " << r.stop_reason << " after " << r.history.size() - 1 << " steps");
      CHECK(int(r.history.size()) <= o.max_iterations + 1);
      CHECK((r.stop_reason == "level set vanished" || r.stop_reason == "distance stalled" ||
             r.stop_reason == "distance rising" || r.stop_reason == "at rest" ||
             r.stop_reason == "iteration cap"));
      for (double c : r.level_set.coefficients()) CHECK(std::isfinite(c));
      // The kept iterate is no farther from the data than the start.
      CHECK(r.history[r.best_iteration].mean_distance <= r.history.front().mean_distance);
    }
  }
}

TEST_CASE("bad input: a level set with no zero set stops at once", "[evolution][bad]") {
  // f > 0 everywhere: no zero-set sample, the documented stop reason, the initial coefficients kept.
  const std::vector<Vec3> points = test::sphere_data(300);
  auto basis = std::make_shared<TSplineBasis>(build_octree(points, test::test_options("distance", "eigen_cg").tmesh));
  const TSpline empty(basis, std::vector<double>(basis->size(), 1.0));
  EvolutionOptions o = test::test_options("distance", "eigen_cg");
  o.final_refinement = false;
  const LevelSetResult r = evolve_level_set(empty, points, o);
  CHECK(r.stop_reason == "level set vanished");
  CHECK(r.history.size() == 1);
  CHECK(r.level_set.coefficients() == empty.coefficients());
}
