// The octree T-mesh: refinement follows the data, 2:1 balance, leaves tile the domain, O(1) lookup
// agrees with the cells, options and bad input are reported clearly.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "algorithms/tspline/octree.hpp"
#include "framework/core/error.hpp"
#include "tests/tspline/fixtures.hpp"

using namespace dtsl;

namespace {

/// Sum of leaf volumes in finest-level units (must equal resolution^3 for a tiling).
double leaf_volume(const Octree& t) {
  double v = 0;
  for (int l = 0; l < t.leaf_count(); ++l) v += std::pow(double(t.cell_size(t.leaf(l).level)), 3);
  return v;
}

bool box_contains(const BoundingBox& b, const Vec3& x) {
  return (x.array() >= b.min.array()).all() && (x.array() <= b.max.array()).all();
}

/// Number of data points inside the leaf's half-open box.
int points_in(const Octree& t, int leaf, const std::vector<Vec3>& points) {
  int n = 0;
  for (const Vec3& p : points)
    if (t.locate(p) == leaf) ++n;
  return n;
}

}  // namespace

TEST_CASE("T-mesh options: defaults are valid, out-of-range fields are named", "[tspline][octree]") {
  TMeshOptions o;
  CHECK_NOTHROW(o.check());
  for (int bad : {0, -1, kMaxOctreeDepth + 1}) {
    TMeshOptions b;
    b.max_depth = bad;
    CHECK_THROWS_AS(b.check(), ConfigError);
    CHECK_THROWS_WITH(b.check(), Catch::StartsWith("max_depth"));
  }
  TMeshOptions b;
  b.points_per_cell = 0;
  CHECK_THROWS_WITH(b.check(), Catch::StartsWith("points_per_cell"));
  b = TMeshOptions();
  b.margin = -0.1;
  CHECK_THROWS_WITH(b.check(), Catch::StartsWith("margin"));
  b = TMeshOptions();
  b.balance = "diagonal";
  CHECK_THROWS_WITH(b.check(), Catch::StartsWith("balance"));
  b = TMeshOptions();
  b.max_depth = 11;
  CHECK_THROWS_AS(build_octree(test::nonuniform_points(), b), ConfigError);
}

TEST_CASE("adaptive T-mesh follows the data density, tiles the domain and is 2:1 balanced", "[tspline][octree]") {
  const auto& points = test::nonuniform_points();
  for (const char* balance : {"face", "edge", "vertex"}) {
    SECTION(balance) {
      TMeshOptions o;
      o.max_depth = 5;
      o.points_per_cell = 16;
      o.balance = balance;
      const Octree t = build_octree(points, o);
      INFO("leaves " << t.leaf_count());
      CHECK(leaf_volume(t) == std::pow(double(t.resolution()), 3));
      CHECK(is_balanced(t, balance_from_string(balance)));
      CHECK(t.finest_leaf_level() == 5);
      // Refinement rule: a leaf above max_depth holds at most points_per_cell points.
      for (int l = 0; l < t.leaf_count(); ++l) {
        CHECK(t.leaf(l).level >= o.min_depth);
        if (t.leaf(l).level < o.max_depth) CHECK(points_in(t, l, points) <= o.points_per_cell);
      }
      // Non-uniform: T-junctions exist (a leaf next to a finer leaf across a face).
      CHECK(!test::t_junction_faces(t).empty());
      // Locate: the leaf's box holds the point, at random points and at the domain's corners.
      for (const Vec3& x : test::random_points(t.domain(), 2000, 3)) CHECK(box_contains(t.leaf_box(t.locate(x)), x));
    }
  }
}

TEST_CASE("face balance alone lets edge neighbours differ by two levels; vertex balance does not", "[tspline][octree]") {
  // Evidence for the balance option's documentation: face balance is weaker than edge/vertex balance.
  const Octree face = build_octree(test::nonuniform_points(), [] {
    TMeshOptions o;
    o.max_depth = 5;
    o.points_per_cell = 16;
    return o;
  }());
  CHECK(is_balanced(face, Balance::face));
  const Octree vertex = refine_octree(face, {}, Balance::vertex);
  CHECK(is_balanced(vertex, Balance::vertex));
  CHECK(vertex.leaf_count() >= face.leaf_count());
}

TEST_CASE("uniform T-mesh is the full octree", "[tspline][octree]") {
  for (int depth : {1, 2, 4}) {
    const Octree t = uniform_octree(depth, 0.25);
    CHECK(t.leaf_count() == (1 << (3 * depth)));
    for (int l = 0; l < t.leaf_count(); ++l) CHECK(t.leaf(l).level == depth);
    CHECK(t.domain().min.x() == -1.25);
    CHECK(t.domain().max.z() == 1.25);
  }
}

TEST_CASE("deep octrees: locate works beyond the lookup table's level", "[tspline][octree]") {
  // max_depth 9 > 7: lookups descend below the table. Points on a small sphere refine to level 9.
  TMeshOptions o;
  o.max_depth = 9;
  o.points_per_cell = 4;
  const auto points = test::sphere_points(3000, 0.05, Vec3(0.3, -0.2, 0.1), 5);
  const Octree t = build_octree(points, o);
  CHECK(t.finest_leaf_level() == 9);
  CHECK(is_balanced(t, Balance::face));
  for (const Vec3& p : points) CHECK(box_contains(t.leaf_box(t.locate(p)), p));
  for (const Vec3& x : test::random_points(t.domain(), 2000, 4)) CHECK(box_contains(t.leaf_box(t.locate(x)), x));
}

TEST_CASE("T-mesh bad input: too few, coincident, non-finite or unnormalised points", "[tspline][octree]") {
  TMeshOptions o;
  const std::vector<Vec3> three = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  CHECK_THROWS_AS(build_octree(three, o), AlgorithmError);
  CHECK_THROWS_WITH(build_octree(three, o), Catch::Contains("at least 4") && Catch::Contains("got 3"));
  CHECK_THROWS_WITH(build_octree({}, o), Catch::Contains("at least 4"));

  const std::vector<Vec3> same(100, Vec3(0.2, 0.3, -0.4));
  CHECK_THROWS_AS(build_octree(same, o), AlgorithmError);
  CHECK_THROWS_WITH(build_octree(same, o), Catch::Contains("coincide"));

  std::vector<Vec3> nan = test::sphere_points(50, 0.5, Vec3::Zero(), 1);
  nan[17].y() = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(build_octree(nan, o), Catch::Contains("point 17") && Catch::Contains("NaN"));

  std::vector<Vec3> outside = test::sphere_points(50, 0.5, Vec3::Zero(), 1);
  outside[3] = Vec3(0, 0, 2.0);
  CHECK_THROWS_WITH(build_octree(outside, o), Catch::Contains("point 3") && Catch::Contains("outside the domain"));
}

TEST_CASE("T-mesh of points on a plane or a line: refined along them only (documented result)", "[tspline][octree]") {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> plane, line;
  for (int k = 0; k < 4000; ++k) {
    plane.emplace_back(u(rng), u(rng), 0.1);
    line.emplace_back(u(rng), -0.3, 0.2);
  }
  TMeshOptions o;
  o.max_depth = 5;
  o.points_per_cell = 8;
  for (const auto* points : {&plane, &line}) {
    const Octree t = build_octree(*points, o);
    CHECK(is_balanced(t, Balance::face));
    CHECK(t.finest_leaf_level() == 5);
    // Leaves far from the data (beyond the balance grading, 3 coarse cells) stay at min_depth.
    const double coarse = t.side() / 8;
    for (int l = 0; l < t.leaf_count(); ++l) {
      const Vec3 c = t.leaf_box(l).center();
      const bool far = points == &plane ? std::abs(c.z() - 0.1) > 3 * coarse
                                        : std::hypot(c.y() + 0.3, c.z() - 0.2) > 3 * coarse;
      if (far) CHECK(t.leaf(l).level == o.min_depth);
    }
    // The T-spline on it is well defined (positivity checked in tspline_test for general meshes).
    const TSplineBasis basis(t);
    std::vector<double> ones(basis.size(), 1.0);
    for (const Vec3& x : test::random_points(t.domain(), 200, 2)) CHECK(basis.evaluate(ones.data(), x) == Approx(1.0));
  }
}

TEST_CASE("octree_from_leaves rebuilds a T-mesh and rejects overlaps and gaps", "[tspline][octree]") {
  const Octree t = build_octree(test::nonuniform_points(), TMeshOptions());
  std::vector<LeafRecord> leaves;
  for (int l = 0; l < t.leaf_count(); ++l) leaves.push_back({t.leaf(l).level, t.leaf(l).origin});
  const Octree r = octree_from_leaves(t.domain_min(), t.side(), t.max_depth(), leaves);
  REQUIRE(r.leaf_count() == t.leaf_count());
  for (int l = 0; l < t.leaf_count(); ++l) {
    CHECK(r.leaf(l).level == t.leaf(l).level);
    CHECK(r.leaf(l).origin == t.leaf(l).origin);
  }
  auto gap = leaves;
  gap.pop_back();
  CHECK_THROWS_WITH(octree_from_leaves(t.domain_min(), t.side(), t.max_depth(), gap), Catch::Contains("gap"));
  auto overlap = leaves;
  overlap.push_back({0, {0, 0, 0}});
  CHECK_THROWS_WITH(octree_from_leaves(t.domain_min(), t.side(), t.max_depth(), overlap), Catch::Contains("overlaps"));
  auto twice = leaves;
  twice.push_back(leaves[5]);
  CHECK_THROWS_AS(octree_from_leaves(t.domain_min(), t.side(), t.max_depth(), twice), AlgorithmError);
  auto misaligned = leaves;
  misaligned[0].origin[0] += 1;
  CHECK_THROWS_WITH(octree_from_leaves(t.domain_min(), t.side(), t.max_depth(), misaligned), Catch::Contains("lattice"));
}

TEST_CASE("refine_octree splits the chosen leaves and rebalances", "[tspline][octree]") {
  const Octree t = build_octree(test::nonuniform_points(), TMeshOptions());
  std::vector<int> chosen;
  for (int l = 0; l < t.leaf_count(); l += 37)
    if (t.leaf(l).level < t.max_depth()) chosen.push_back(l);
  const Octree r = refine_octree(t, chosen, Balance::face);
  CHECK(is_balanced(r, Balance::face));
  CHECK(leaf_volume(r) == std::pow(double(r.resolution()), 3));
  for (int l : chosen) {
    // The chosen cell is now split: the leaf at its origin is one level finer.
    const Octree::Cell& before = t.leaf(l);
    CHECK(r.leaf(r.leaf_at(before.origin)).level == before.level + 1);
  }
  CHECK_THROWS_AS(refine_octree(t, {t.leaf_count()}, Balance::face), AlgorithmError);
}
