// The coarse-to-fine rounds (coarse_to_fine.hpp): refine near the data, evolve again. On the
// non-uniformly sampled torus a round must give a finer T-mesh near the data, bring the level set
// closer to the data than the first evolution left it, and keep the genus; refine_toward_data must
// leave f unchanged up to the transfer's O(h^2) and split only near the data.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <map>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "algorithms/evolution/coarse_to_fine.hpp"
#include "algorithms/evolution/evolution.hpp"
#include "algorithms/evolution/level_set_transfer.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/evolution/fixtures.hpp"

using namespace dtsl;

TEST_CASE("coarse-to-fine: a round refines near the data, fits closer, keeps genus 1", "[evolution][fine]") {
  const std::vector<Vec3>& points = test::torus_data();
  EvolutionOptions o = test::test_options("distance_balloon", "eigen_cg", 5);
  o.tmesh.points_per_cell = 64;  // coarse first T-mesh: level 4 at most
  o.final_refinement = false;
  EvolutionOptions single = o;
  o.fine.levels = 1;
  const LevelSetResult coarse = compute_level_set(points, single);
  const LevelSetResult fine = compute_level_set(points, o);
  INFO(fine.summary["rounds"].dump());
  REQUIRE(fine.summary["rounds"].size() == 2);
  CHECK(fine.history.back().round == 1);
  // Each round's record counts its own steps' solver work (summed from the history of that round).
  for (int round = 0; round < 2; ++round) {
    long iterations = 0;
    int unknowns = 0;
    for (const IterationRecord& r : fine.history)
      if (r.round == round && r.solve) {
        iterations += r.solve->iterations;
        unknowns = std::max(unknowns, r.unknowns);
      }
    CHECK(fine.summary["rounds"][round]["solver_iterations"].get<long>() == iterations);
    CHECK(fine.summary["rounds"][round]["unknowns"].get<int>() == unknowns);
    CHECK(iterations > 0);
  }
  CHECK(fine.summary["rounds"][1]["unknowns"].get<int>() > fine.summary["rounds"][0]["unknowns"].get<int>());
  CHECK(fine.level_set.tmesh().finest_leaf_level() == coarse.level_set.tmesh().finest_leaf_level() + 1);
  CHECK(fine.level_set.basis().size() > coarse.level_set.basis().size());
  const test::NewtonDistances before = test::newton_distances(coarse.level_set, points);
  const test::NewtonDistances after = test::newton_distances(fine.level_set, points);
  INFO("mean Newton distance " << before.mean << " -> " << after.mean);
  CHECK(after.mean < before.mean);
  const MeshStats s = mesh_stats(test::zero_set_mesh(fine.level_set, points));
  CHECK(s.genus == 1.0);
  CHECK(s.components == 1);
}

TEST_CASE("refine_toward_data: splits only near the data, f moves by much less than a cell", "[evolution][fine]") {
  const std::vector<Vec3>& points = test::torus_data();
  EvolutionOptions o = test::test_options("distance_balloon", "eigen_cg", 5);
  o.final_refinement = false;
  const LevelSetResult r = compute_level_set(points, o);
  CoarseToFineOptions fine;
  const int level = r.level_set.tmesh().finest_leaf_level() + 1;
  const TSpline refined = refine_toward_data(r.level_set, points, level, fine);
  REQUIRE(refined.basis().size() > r.level_set.basis().size());
  const Octree& tree = refined.tmesh();
  // The torus's hole centre and the domain's corner hold no data: not split to the new level.
  CHECK(tree.leaf(tree.locate(Vec3(0, 0, 0))).level < level);
  CHECK(tree.leaf(tree.locate(Vec3(1.2, 1.2, 1.2))).level < level);
  for (std::size_t k = 0; k < points.size(); k += 20) {
    const double side = r.level_set.tmesh().leaf_side(r.level_set.tmesh().locate(points[k]));
    CHECK(std::abs(refined.evaluate(points[k]) - r.level_set.evaluate(points[k])) < 0.25 * side);  // quasi-interpolation: O(h^2)
  }
  // Nothing to split any more at the level the T-mesh already has everywhere near the data: f itself.
  const TSpline again = refine_toward_data(r.level_set, points, r.level_set.tmesh().finest_leaf_level() - 10, fine);
  CHECK(again.shared_basis() == r.level_set.shared_basis());
  CoarseToFineOptions bad;
  bad.levels = -1;
  CHECK_THROWS_WITH(refine_toward_data(r.level_set, points, level, bad), Catch::Contains("levels"));
}

TEST_CASE("coarse-to-fine: the rounds evolve with fine_velocity and its own options", "[evolution][fine]") {
  const std::vector<Vec3>& points = test::torus_data();
  EvolutionOptions o = test::test_options("geodesic", "eigen_cg", 5);
  o.tmesh.points_per_cell = 64;
  o.final_refinement = false;
  o.fine.levels = 1;
  apply_assignment(o, "fine_velocity", "distance_balloon", "evolution");
  apply_assignment(o, "fine_velocity_beta", "0.3", "evolution");
  CHECK(to_json(o)["fine_velocity_beta"].get<double>() == 0.3);
  CHECK(to_json(o)["velocity_lambda"].get<double>() == 1.0);  // geodesic's own options stay the first evolution's
  const LevelSetResult r = compute_level_set(points, o);
  REQUIRE(r.summary["rounds"].size() == 2);
  CHECK(r.summary["rounds"][0]["velocity"] == "geodesic");
  CHECK(r.summary["rounds"][1]["velocity"] == "distance_balloon");
  CHECK(r.summary["options"]["velocity"] == "geodesic");
  CHECK(r.summary["options"]["fine_velocity"] == "distance_balloon");
  // The record gives each velocity's own options, not the rounds' under the first velocity's names.
  CHECK(r.summary["options"]["velocity_lambda"].get<double>() == 1.0);
  CHECK(r.summary["options"]["fine_velocity_beta"].get<double>() == 0.3);
  const MeshStats s = mesh_stats(test::zero_set_mesh(r.level_set, points));
  CHECK(s.genus == 1.0);
  CHECK(s.components == 1);
  // A different round velocity is a different flow: the option reaches the rounds.
  EvolutionOptions same = o;
  apply_assignment(same, "fine_velocity", "\"\"", "evolution");  // YAML: fine_velocity: ""
  const LevelSetResult g = compute_level_set(points, same);
  CHECK(g.summary["rounds"][1]["velocity"] == "geodesic");
  CHECK(g.level_set.coefficients() != r.level_set.coefficients());
}

TEST_CASE("fine_velocity: unknown names and bad options are ConfigErrors naming the key", "[evolution][fine][bad]") {
  EvolutionOptions o;
  const auto message = [&](const std::string& key, const std::string& value) {
    EvolutionOptions copy = o;
    try {
      apply_assignment(copy, key, value, "evolution");
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(message("fine_velocity", "no_such_velocity"), Catch::Contains("fine_velocity") && Catch::Contains("no_such_velocity"));
  // Its options exist only once it is named, and are range-checked under their prefix.
  CHECK_THAT(message("fine_velocity_beta", "0.3"), Catch::Contains("unknown key"));
  apply_assignment(o, "fine_velocity", "distance_balloon", "evolution");
  CHECK_THAT(message("fine_velocity_beta", "2"), Catch::Contains("fine_velocity_beta"));
  CHECK(message("fine_velocity_beta", "0.5") == "no error");
}

TEST_CASE("transfer: unchanged knots keep their coefficient, changed ones take f at their Greville point",
          "[evolution][fine][transfer]") {
  const std::vector<Vec3>& points = test::torus_data();
  EvolutionOptions o = test::test_options("distance_balloon", "eigen_cg", 5);
  o.final_refinement = false;
  const LevelSetResult r = compute_level_set(points, o);
  const TSpline& old = r.level_set;
  // Split every leaf the data touch, one level.
  Octree tree = old.tmesh();
  std::vector<int> split;
  for (const Vec3& p : points) split.push_back(tree.locate(p));
  std::sort(split.begin(), split.end());
  split.erase(std::unique(split.begin(), split.end()), split.end());
  const Octree refined = refine_octree(tree, split, balance_of(tree));
  TransferReport report;
  const TSpline moved = transfer_level_set(old, refined, &report);
  INFO(to_json(report).dump());
  CHECK(report.changed > 0);
  std::map<Int3, int> old_index;
  for (int j = 0; j < old.basis().size(); ++j) old_index.emplace(old.basis().vertex(j), j);
  int kept = 0, changed = 0;
  for (int i = 0; i < moved.basis().size(); ++i) {
    const auto it = old_index.find(moved.basis().vertex(i));
    if (it == old_index.end() || !(old.basis().knots(it->second) == moved.basis().knots(i))) {
      ++changed;
      CHECK(moved.coefficients()[i] == old.evaluate(moved.basis().greville(i)));
      continue;
    }
    ++kept;
    CHECK(moved.coefficients()[i] == old.coefficients()[it->second]);
  }
  CHECK(kept > 0);
  CHECK(changed == report.changed);
}

TEST_CASE("coarse-to-fine: a round moves f onto the refined T-mesh by the transfer", "[evolution][fine][transfer]") {
  const std::vector<Vec3>& points = test::torus_data();
  EvolutionOptions o = test::test_options("distance_balloon", "eigen_cg", 5);
  o.final_refinement = false;
  const LevelSetResult r = compute_level_set(points, o);
  const int level = r.level_set.tmesh().finest_leaf_level() + 1;
  const TSpline refined = refine_toward_data(r.level_set, points, level, o.fine);
  REQUIRE(refined.basis().size() > r.level_set.basis().size());
  CHECK(refined.coefficients() == transfer_level_set(r.level_set, refined.tmesh()).coefficients());
}
