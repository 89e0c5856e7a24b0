// The final refinement ([55], docs/design.md §1): refines where the surface meets the data, keeps f where
// the T-mesh did not change, brings the level set closer to the data; callable again with focus points
// (Phase 2, where displacement flips triangles).
#include <catch2/catch.hpp>
#include <cmath>

#include "algorithms/evolution/final_refinement.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "tests/evolution/fixtures.hpp"

using namespace dtsl;

namespace {

/// The evolved (unrefined) level set of the non-uniform torus, computed once.
const LevelSetResult& evolved_torus() {
  static const LevelSetResult r = [] {
    EvolutionOptions o = test::test_options("distance_balloon", "eigen_cg", 5);
    o.tmesh.points_per_cell = 32;
    o.final_refinement = false;
    return compute_level_set(test::torus_data(), o);
  }();
  return r;
}

std::unique_ptr<LevelSetSolver> ldlt() {
  register_level_set_solvers();
  return level_set_solvers().create("eigen_ldlt", "test");
}

// Refinement down to the T-mesh's max_depth.
FinalRefinementOptions to_finest_level() {
  FinalRefinementOptions o;
  o.target_level = evolved_torus().level_set.tmesh().max_depth();
  return o;
}

// The data point with the largest x: a focus for refining around it only.
Vec3 rightmost(const std::vector<Vec3>& points) {
  return *std::max_element(points.begin(), points.end(), [](const Vec3& a, const Vec3& b) { return a.x() < b.x(); });
}

}  // namespace

TEST_CASE("final refinement: finer cells along the surface near data, closer to the data", "[evolution][refine]") {
  const LevelSetResult& evolved = evolved_torus();
  const std::vector<Vec3>& points = test::torus_data();
  REQUIRE(evolved.level_set.tmesh().finest_leaf_level() > 3);  // the dense side reached a finer level
  FinalRefinementOptions o;
  auto solver = ldlt();
  const RefinedLevelSet r = refine_level_set(evolved.level_set, points, o, *solver);
  INFO(to_json(r.report).dump());
  CHECK(r.report.rounds >= 1);
  CHECK(r.report.leaves_split > 0);
  CHECK(r.report.control_points_after > r.report.control_points_before);
  CHECK(r.report.target_level == evolved.level_set.tmesh().finest_leaf_level());
  CHECK(r.level_set.tmesh().finest_leaf_level() == r.report.target_level);
  CHECK(is_balanced(r.level_set.tmesh(), Balance::face));
  // Every leaf the refined zero set crosses near the data is at the target level now.
  const test::NewtonDistances before = test::newton_distances(evolved.level_set, points);
  const test::NewtonDistances after = test::newton_distances(r.level_set, points);
  INFO("Newton distance mean " << before.mean << " -> " << after.mean << ", max " << before.max << " -> " << after.max);
  CHECK(after.mean < 0.8 * before.mean);
  CHECK(after.max < before.max);
  CHECK(r.report.after.mean < r.report.before.mean);
  const MeshStats s = mesh_stats(test::zero_set_mesh(r.level_set, points));
  CHECK(s.genus == 1.0);
  CHECK(s.components == 1);
}

TEST_CASE("final refinement: the transfer keeps f where the T-mesh did not change", "[evolution][refine]") {
  const LevelSetResult& evolved = evolved_torus();
  const std::vector<Vec3>& points = test::torus_data();
  FinalRefinementOptions o;
  o.fit_iterations = 0;  // refine and transfer only
  auto solver = ldlt();
  const RefinedLevelSet r = refine_level_set(evolved.level_set, points, o, *solver);
  REQUIRE(r.report.leaves_split > 0);
  // Far from the surface (corners of the domain) no leaf was split: f is unchanged there.
  const BoundingBox box = evolved.level_set.domain();
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 x((corner & 1) ? box.max.x() - 0.05 : box.min.x() + 0.05, (corner & 2) ? box.max.y() - 0.05 : box.min.y() + 0.05,
                 (corner & 4) ? box.max.z() - 0.05 : box.min.z() + 0.05);
    CHECK(r.level_set.evaluate(x) == Approx(evolved.level_set.evaluate(x)).margin(1e-12));
  }
  // Near the surface the quasi-interpolant (O(h^2)) is close to the old f: well within a cell size (the
  // refined T-splines do not contain the coarse one, so no transfer is exact; the fit follows).
  const Octree& tree = r.level_set.tmesh();
  for (std::size_t k = 0; k < points.size(); k += 25)
    CHECK(std::abs(r.level_set.evaluate(points[k]) - evolved.level_set.evaluate(points[k])) <
          0.4 * tree.leaf_side(tree.locate(points[k])));
}

TEST_CASE("final refinement: focus points refine only near them (Phase 2 flips)", "[evolution][refine]") {
  const LevelSetResult& evolved = evolved_torus();
  const std::vector<Vec3>& points = test::torus_data();
  const FinalRefinementOptions o = to_finest_level();
  auto solver = ldlt();
  const Vec3 focus = rightmost(points);
  const RefinedLevelSet local = refine_level_set(evolved.level_set, points, o, *solver, {focus});
  const RefinedLevelSet everywhere = refine_level_set(evolved.level_set, points, o, *solver);
  CHECK(local.report.leaves_split > 0);
  CHECK(local.report.leaves_split < everywhere.report.leaves_split);
  const Octree& tree = local.level_set.tmesh();
  CHECK(tree.leaf(tree.locate(focus)).level == o.target_level);
  const Vec3 opposite(-focus.x(), focus.y(), focus.z());
  CHECK(tree.leaf(tree.locate(opposite)).level < o.target_level);
}

TEST_CASE("final refinement: with focus points only the control points the refinement changed are fitted",
          "[evolution][refine]") {
  const LevelSetResult& evolved = evolved_torus();
  const std::vector<Vec3>& points = test::torus_data();
  const FinalRefinementOptions o = to_finest_level();
  auto solver = ldlt();
  const Vec3 focus = rightmost(points);
  const RefinedLevelSet local = refine_level_set(evolved.level_set, points, o, *solver, {focus});
  REQUIRE(local.report.rounds > 0);
  const std::vector<char>& changed = local.report.transfer.changed_flags;
  REQUIRE(changed.size() == local.level_set.coefficients().size());
  int held = 0, moved = 0;
  for (std::size_t i = 0; i < changed.size(); ++i) {
    if (changed[i]) {
      moved += local.level_set.coefficients()[i] != local.transferred[i];
    } else {
      ++held;
      CHECK(local.level_set.coefficients()[i] == local.transferred[i]);
    }
  }
  CHECK(held > 0);
  CHECK(moved > 0);  // the fit did move the changed part
  // Far from the focus f is the input's, to rounding: the zero set there stays where it was.
  const Vec3 opposite(-focus.x(), focus.y(), focus.z());
  CHECK(local.level_set.evaluate(opposite) == Approx(evolved.level_set.evaluate(opposite)).margin(1e-12));
}

TEST_CASE("final refinement: nothing to split fits anyway, or with skip_fit returns f unchanged", "[evolution][refine]") {
  const LevelSetResult& evolved = evolved_torus();
  const std::vector<Vec3>& points = test::torus_data();
  FinalRefinementOptions o;
  auto solver = ldlt();
  // Refined once to the target level, the level set has nothing left to split there.
  const RefinedLevelSet once = refine_level_set(evolved.level_set, points, o, *solver);
  REQUIRE(once.report.rounds >= 1);
  o.target_level = once.report.target_level;
  const RefinedLevelSet fitted = refine_level_set(once.level_set, points, o, *solver);
  CHECK(fitted.report.rounds == 0);
  CHECK(fitted.report.solves.size() == 1);  // the default: the fit still runs
  CHECK(fitted.level_set.coefficients() != once.level_set.coefficients());
  const RefinedLevelSet skipped =
      refine_level_set(once.level_set, points, o, *solver, {}, WhenNothingToSplit::skip_fit);
  CHECK(skipped.report.rounds == 0);
  CHECK(skipped.report.solves.empty());
  CHECK(skipped.level_set.coefficients() == once.level_set.coefficients());
  CHECK(skipped.level_set.shared_basis() == once.level_set.shared_basis());
  CHECK(skipped.transferred == once.level_set.coefficients());
  // With skip_fit and something to split, it refines and fits as always.
  const RefinedLevelSet refined =
      refine_level_set(evolved.level_set, points, FinalRefinementOptions{}, *solver, {}, WhenNothingToSplit::skip_fit);
  CHECK(refined.report.rounds == once.report.rounds);
  CHECK(refined.level_set.coefficients() == once.level_set.coefficients());
}

TEST_CASE("final refinement: options are checked, no points is an error", "[evolution][refine][bad]") {
  const LevelSetResult& evolved = evolved_torus();
  auto solver = ldlt();
  FinalRefinementOptions o;
  CHECK_THROWS_AS(refine_level_set(evolved.level_set, {}, o, *solver), AlgorithmError);
  o.fit_iterations = -1;
  CHECK_THROWS_AS(refine_level_set(evolved.level_set, test::torus_data(), o, *solver), ConfigError);
  FinalRefinementOptions p;
  CHECK_THROWS_WITH(apply_assignment(p, "w_distance", "-1", "refine"), Catch::Contains("w_distance"));
}
