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
  FinalRefinementOptions o;
  o.target_level = evolved.level_set.tmesh().max_depth();
  auto solver = ldlt();
  // The data point with the largest x: refine around it only.
  const Vec3 focus = *std::max_element(points.begin(), points.end(), [](const Vec3& a, const Vec3& b) { return a.x() < b.x(); });
  const RefinedLevelSet local = refine_level_set(evolved.level_set, points, o, *solver, {focus});
  const RefinedLevelSet everywhere = refine_level_set(evolved.level_set, points, o, *solver);
  CHECK(local.report.leaves_split > 0);
  CHECK(local.report.leaves_split < everywhere.report.leaves_split);
  const Octree& tree = local.level_set.tmesh();
  CHECK(tree.leaf(tree.locate(focus)).level == o.target_level);
  const Vec3 opposite(-focus.x(), focus.y(), focus.z());
  CHECK(tree.leaf(tree.locate(opposite)).level < o.target_level);
}

TEST_CASE("final refinement: a local fit around focus points moves only the control points over new leaves",
          "[evolution][refine]") {
  const LevelSetResult& evolved = evolved_torus();
  const std::vector<Vec3>& points = test::torus_data();
  FinalRefinementOptions o;
  o.target_level = evolved.level_set.tmesh().max_depth();
  CHECK_FALSE(o.local_fit);  // off by default
  o.local_fit = true;
  auto solver = ldlt();
  const Vec3 focus = *std::max_element(points.begin(), points.end(), [](const Vec3& a, const Vec3& b) { return a.x() < b.x(); });
  const RefinedLevelSet local = refine_level_set(evolved.level_set, points, o, *solver, {focus});
  REQUIRE(local.report.leaves_split > 0);
  INFO(to_json(local.report).dump());
  CHECK(local.report.free_control_points > 0);
  CHECK(local.report.free_control_points < local.report.control_points_after / 2);
  // Outside the free set the coefficients are the transferred ones; inside, the fit moved some.
  const std::vector<double>& c = local.level_set.coefficients();
  int moved = 0;
  for (std::size_t i = 0; i < c.size(); ++i) moved += c[i] != local.transferred[i];
  CHECK(moved > 0);
  CHECK(moved <= local.report.free_control_points);
  // Every moved control point is free: its support overlaps a leaf the refinement created.
  const TSplineBasis& refined = local.level_set.basis();
  const Octree& before_tree = evolved.level_set.tmesh();
  std::vector<char> free(c.size(), 0);
  for (int l = 0; l < refined.octree().leaf_count(); ++l) {
    const Octree::Cell& cell = refined.octree().leaf(l);
    if (before_tree.leaf(before_tree.leaf_at(cell.origin)).level < cell.level)
      for (int i : refined.support(l)) free[std::size_t(i)] = 1;
  }
  for (std::size_t i = 0; i < c.size(); ++i)
    if (c[i] != local.transferred[i]) CHECK(free[i]);
  // So f is the transferred f far from the focus (the other side of the torus) ...
  const Vec3 opposite(-focus.x(), focus.y(), focus.z());
  const TSpline transferred(local.level_set.shared_basis(), local.transferred);
  CHECK(local.level_set.evaluate(opposite) == Approx(transferred.evaluate(opposite)).margin(1e-12));
  // ... and near it the data are closer than to the evolved f, about as close as after a global fit
  // (sums of |f| / |grad f| over the data within 0.1 of the focus).
  FinalRefinementOptions all_options = o;
  all_options.local_fit = false;
  const RefinedLevelSet all = refine_level_set(evolved.level_set, points, all_options, *solver, {focus});
  CHECK(all.report.free_control_points == 0);
  const auto near_distance = [&](const ImplicitFunction& f) {
    double sum = 0.0;
    for (const Vec3& p : points)
      if ((p - focus).norm() < 0.1) {
        Vec3 g;
        const double v = f.evaluate(p, &g);
        sum += std::abs(v) / g.norm();
      }
    return sum;
  };
  const double d_evolved = near_distance(evolved.level_set), d_local = near_distance(local.level_set),
               d_global = near_distance(all.level_set);
  INFO("near the focus: evolved " << d_evolved << ", local fit " << d_local << ", global fit " << d_global);
  CHECK(d_local < 0.9 * d_evolved);
  CHECK(d_local < 1.1 * d_global);
  // Without focus points the option changes nothing: the final refinement fits everywhere.
  FinalRefinementOptions global = o;
  global.target_level = -1;
  CHECK(refine_level_set(evolved.level_set, points, global, *solver).report.free_control_points == 0);
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
  CHECK_THROWS_WITH(apply_assignment(p, "smoothness", "thin_plate", "refine"), Catch::Contains("smoothness"));
  FinalRefinementOptions q;
  CHECK_THROWS_WITH(apply_assignment(q, "transfer", "nearest", "refine"),
                    Catch::Contains("transfer") && Catch::Contains("nearest"));
}

TEST_CASE("final refinement: the least-squares transfer starts the fit closer to the evolved f", "[evolution][refine][transfer]") {
  const LevelSetResult& evolved = evolved_torus();
  const std::vector<Vec3>& points = test::torus_data();
  FinalRefinementOptions o;
  o.fit_iterations = 0;  // the transfer alone
  auto solver = ldlt();
  const RefinedLevelSet quasi = refine_level_set(evolved.level_set, points, o, *solver);
  o.transfer = "least_squares";
  const RefinedLevelSet fitted = refine_level_set(evolved.level_set, points, o, *solver);
  REQUIRE(quasi.report.leaves_split == fitted.report.leaves_split);
  CHECK(fitted.report.transfer.method == "least_squares");
  CHECK(quasi.report.transfer.method == "quasi_interpolation");
  CHECK(fitted.report.transfer.converged);
  CHECK(fitted.report.transfer.samples > 0);
  CHECK(to_json(fitted.report)["transfer"]["method"] == "least_squares");
  // On the data, the transferred f differs from the evolved one by less (sum of squares).
  double quasi_sq = 0.0, fitted_sq = 0.0;
  for (const Vec3& p : points) {
    const double f0 = evolved.level_set.evaluate(p);
    quasi_sq += std::pow(quasi.level_set.evaluate(p) - f0, 2);
    fitted_sq += std::pow(fitted.level_set.evaluate(p) - f0, 2);
  }
  INFO("sum of squares " << quasi_sq << " -> " << fitted_sq);
  CHECK(fitted_sq < 0.5 * quasi_sq);
}
