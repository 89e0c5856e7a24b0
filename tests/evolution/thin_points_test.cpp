// thin_points and level_set_data: the level-set stage's data at large inputs (thin_points.hpp,
// EvolutionOptions::max_points).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "algorithms/evolution/evolution.hpp"
#include "algorithms/evolution/thin_points.hpp"
#include "framework/core/error.hpp"

using namespace dtsl;

namespace {

constexpr double kCell = 0.1;

/// `dense` points in the cell [0, 0.1)^3, then `sparse` points alone in cells along the x axis.
std::vector<Vec3> dense_and_sparse(int dense, int sparse) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.001, 0.099);
  std::vector<Vec3> p;
  for (int k = 0; k < dense; ++k) p.emplace_back(u(rng), u(rng), u(rng));
  for (int k = 0; k < sparse; ++k) p.emplace_back(0.35 + 0.2 * k, 0.05, 0.05);
  std::shuffle(p.begin(), p.end(), rng);
  return p;
}

std::map<long, int> per_cell(const std::vector<Vec3>& p) {
  std::map<long, int> count;
  for (const Vec3& x : p) ++count[long(std::floor(x.x() / kCell)) * 1000000 + long(std::floor(x.y() / kCell)) * 1000 + long(std::floor(x.z() / kCell))];
  return count;
}

}  // namespace

TEST_CASE("thin_points: sparse cells keep all their points, dense ones are capped, within max_points",
          "[evolution][thin]") {
  const std::vector<Vec3> all = dense_and_sparse(1000, 50);
  const std::vector<Vec3> kept = thin_points(all, 100, kCell);
  CHECK(kept.size() <= 100);
  CHECK(kept.size() >= 95);
  CHECK(kept == thin_points(all, 100, kCell));  // deterministic
  const std::map<long, int> before = per_cell(all), after = per_cell(kept);
  int capped = 0;
  for (const auto& [cell, n] : before) {
    REQUIRE(after.count(cell));  // no cell loses all its points
    if (n == 1) CHECK(after.at(cell) == 1);
    else capped = after.at(cell);
  }
  CHECK(capped == int(kept.size()) - 50);
  for (const Vec3& x : kept) REQUIRE(std::find(all.begin(), all.end(), x) != all.end());  // input points
}

TEST_CASE("thin_points: the same points whatever the input order", "[evolution][thin]") {
  std::vector<Vec3> all = dense_and_sparse(3000, 40);
  const std::vector<Vec3> kept = thin_points(all, 400, kCell);
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 3; ++trial) {
    std::shuffle(all.begin(), all.end(), rng);
    CHECK(thin_points(all, 400, kCell) == kept);
  }
  std::sort(all.begin(), all.end(), [](const Vec3& a, const Vec3& b) { return a.x() < b.x(); });
  CHECK(thin_points(all, 400, kCell) == kept);
}

TEST_CASE("thin_points: a dense cell's kept points cover it, even when the input comes in scan lines",
          "[evolution][thin]") {
  // A plane z = 0.05 sampled on a 100 x 100 grid over 5 x 5 cells, listed row by row as a scanner
  // would: the first points of a cell in input order all lie on one row of it.
  std::vector<Vec3> grid;
  for (int i = 0; i < 100; ++i)
    for (int j = 0; j < 100; ++j) grid.emplace_back(0.0025 + 0.005 * j, 0.0025 + 0.005 * i, 0.05);
  const std::vector<Vec3> kept = thin_points(grid, 25 * 9, kCell);  // 9 points a cell
  REQUIRE(kept.size() == 25 * 9);
  // Every grid point has a kept point within a sixth of a cell (3 x 3 sub-cells of a third each, the
  // kept point near each one's centre), where one row per cell would leave most of the cell a whole
  // cell's depth away.
  double farthest = 0.0;
  for (const Vec3& x : grid) {
    double nearest = 1e9;
    for (const Vec3& y : kept) nearest = std::min(nearest, (x - y).norm());
    farthest = std::max(farthest, nearest);
  }
  CHECK(farthest < kCell / 6.0 * std::sqrt(2.0) + 1e-9);
}

TEST_CASE("thin_points: all points when max_points is 0 or not smaller; one per cell at the least",
          "[evolution][thin]") {
  const std::vector<Vec3> all = dense_and_sparse(200, 20);
  CHECK(thin_points(all, 0, kCell) == all);
  CHECK(thin_points(all, all.size(), kCell) == all);
  CHECK(thin_points({}, 10, kCell).empty());
  // 21 occupied cells, room for 10: one point per cell, the cap cannot go lower.
  const std::vector<Vec3> one_each = thin_points(all, 10, kCell);
  CHECK(one_each.size() == 21);
  for (const auto& [cell, n] : per_cell(one_each)) CHECK(n == 1);
  CHECK_THROWS_WITH(thin_points(all, 10, 0.0), Catch::Contains("cell"));
}

TEST_CASE("level_set_data: thins on the T-mesh's finest cell, names a non-finite point even if dropped",
          "[evolution][thin][bad]") {
  EvolutionOptions o;
  o.max_points = 100;
  const std::vector<Vec3> all = dense_and_sparse(1000, 0);
  const std::vector<Vec3> kept = level_set_data(all, o);
  CHECK(kept.size() <= 100);
  CHECK(kept.size() > 0);
  std::vector<Vec3> bad = all;
  bad[777] = Vec3(std::nan(""), 0.0, 0.0);
  CHECK_THROWS_WITH(level_set_data(bad, o), Catch::Contains("point 777"));
}

TEST_CASE("evolution max_points: out-of-range values are named", "[evolution][thin][bad]") {
  EvolutionOptions o;
  o.max_points = 50;
  CHECK_THROWS_WITH(o.check(), Catch::Contains("max_points"));
  o.max_points = -1;
  CHECK_THROWS_WITH(o.check(), Catch::Contains("max_points"));
  o.max_points = 0;
  CHECK_NOTHROW(o.check());
}
