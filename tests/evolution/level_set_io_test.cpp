// The stage's output: saved, re-loaded bit-identically, with its history as JSON and
// the T-mesh as line geometry; and EvolutionOptions as a flat, prefixed options struct.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <yaml-cpp/yaml.h>

#include "algorithms/evolution/level_set_io.hpp"
#include "algorithms/tspline/tspline_io.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "tests/evolution/fixtures.hpp"

using namespace dtsl;

TEST_CASE("level-set output: save and load round trip, history JSON, T-mesh lines", "[evolution][io]") {
  const std::vector<Vec3> points = test::sphere_data(600);
  const LevelSetResult r = compute_level_set(points, test::test_options("distance_balloon", "eigen_cg"));
  const std::string dir = (std::filesystem::temp_directory_path() / "dtsl_evolution_io_test").string();
  std::filesystem::create_directories(dir);
  const std::string prefix = dir + "/sphere";
  save_level_set(r, prefix);
  const LoadedLevelSet loaded = load_level_set(prefix);
  REQUIRE(loaded.level_set.basis().size() == r.level_set.basis().size());
  for (std::size_t k = 0; k < points.size(); k += 20) CHECK(loaded.level_set.evaluate(points[k]) == r.level_set.evaluate(points[k]));
  const nlohmann::json& j = loaded.record;
  CHECK(j["history"].size() == r.history.size());
  CHECK(j["stop_reason"] == r.stop_reason);
  CHECK(j["best_iteration"] == r.best_iteration);
  CHECK(j["velocity"] == "distance_balloon");
  CHECK(j["options"]["tmesh_max_depth"] == 4);
  for (const char* key : {"mean_speed", "mean_distance", "max_distance", "min_gradient", "max_gradient", "seconds"})
    CHECK(j["history"][0].contains(key));
  CHECK(j.contains("final_refinement"));
  CHECK(j["evolution_timings"].contains("solve"));
  // T-mesh edges as an OBJ of 'l' records.
  std::ifstream obj(prefix + "_tmesh.obj");
  REQUIRE(obj);
  int lines = 0;
  for (std::string line; std::getline(obj, line);) lines += line.rfind("l ", 0) == 0;
  CHECK(lines == int(tmesh_edges(r.level_set.tmesh()).size()));
  CHECK(lines > 0);
  CHECK_THROWS_AS(load_level_set(dir + "/missing"), FileError);
  std::filesystem::remove_all(dir);
}

TEST_CASE("EvolutionOptions: one flat map configures the stage and its plugins", "[evolution][options]") {
  EvolutionOptions o;
  apply_yaml(o, YAML::Load("{velocity: geodesic, velocity_lambda: 0.5, solver: eigen_ldlt, tmesh_max_depth: 5, "
                           "fine_levels: 2}"),
             "level_set");
  CHECK(o.velocity == "geodesic");
  CHECK(o.tmesh.max_depth == 5);
  CHECK(o.fine.levels == 2);
  const nlohmann::json j = to_json(o);
  CHECK(j["velocity_lambda"] == 0.5);
  // Constants of the method are no options: configs cannot reach them.
  CHECK_THROWS_WITH(apply_yaml(o, YAML::Load("{w_smooth: 0.01}"), "level_set"), Catch::Contains("w_smooth"));
  CHECK(!j.contains("solver_tolerance"));
  CHECK(!j.contains("velocity_beta"));  // the balloon's option is not the geodesic's
  // Copies clone the plugins with their options.
  EvolutionOptions copy = o;
  CHECK(to_json(copy) == j);
  apply_assignment(copy, "velocity_lambda", "0.25", "copy");
  CHECK(to_json(o)["velocity_lambda"] == 0.5);
  // Every field has a doc.
  for (const auto& f : describe(o)) CHECK(!f.doc.empty());
  // Unknown keys and unknown plugins are ConfigErrors naming them.
  CHECK_THROWS_WITH(apply_yaml(o, YAML::Load("{velocity_beta: 0.3}"), "level_set"), Catch::Contains("velocity_beta"));
  EvolutionOptions p;
  CHECK_THROWS_WITH(apply_yaml(p, YAML::Load("{velocity: warp}"), "level_set"), Catch::Contains("warp"));
}
