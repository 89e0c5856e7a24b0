// Narrow gaps between pieces (gap_refinement.hpp): the octree deepened by a level is the same T-mesh;
// the leaves between two pieces closer than two finest cells are split one level below the finest, and
// nothing else is; wider gaps and data in one piece leave the T-mesh alone.
#include <catch2/catch.hpp>

#include <vector>

#include "algorithms/evolution/gap_refinement.hpp"
#include "algorithms/tspline/tspline_basis.hpp"
#include "framework/core/error.hpp"

using namespace dtsl;

namespace {

/// Two square sheets of points parallel to z = 0, `gap` apart around z = 0, piece 0 below and 1 above.
void two_sheets(double gap, std::vector<Vec3>& points, std::vector<int>& piece) {
  points.clear();
  piece.clear();
  for (int s = 0; s < 2; ++s)
    for (int i = 0; i <= 40; ++i)
      for (int j = 0; j <= 40; ++j) {
        points.emplace_back(-0.5 + i / 40.0, -0.5 + j / 40.0, s == 0 ? -gap / 2 : gap / 2);
        piece.push_back(s);
      }
}

Octree data_tree(const std::vector<Vec3>& points) {
  TMeshOptions options;
  options.max_depth = 5;
  options.points_per_cell = 8;
  return build_octree(points, options);
}

double finest_side(const Octree& tree) { return tree.unit() * tree.cell_size(tree.finest_leaf_level()); }

}  // namespace

TEST_CASE("a deepened octree has the same leaves and the same T-spline space", "[gaps]") {
  std::vector<Vec3> points;
  std::vector<int> piece;
  two_sheets(0.1, points, piece);
  const Octree tree = data_tree(points);
  const Octree deep = deepened(tree);
  CHECK(deep.max_depth() == tree.max_depth() + 1);
  REQUIRE(deep.leaf_count() == tree.leaf_count());
  for (int l = 0; l < tree.leaf_count(); ++l) {
    CHECK(deep.leaf(l).level == tree.leaf(l).level);
    CHECK((deep.leaf_box(l).min - tree.leaf_box(l).min).norm() < 1e-12);
    CHECK((deep.leaf_box(l).max - tree.leaf_box(l).max).norm() < 1e-12);
  }
  const TSplineBasis a(tree), b(deep);
  REQUIRE(a.size() == b.size());
  for (int i = 0; i < a.size(); i += 7) CHECK((a.greville(i) - b.greville(i)).norm() < 1e-12);
}

TEST_CASE("leaves across a gap narrower than two finest cells are split one level finer, others not", "[gaps]") {
  std::vector<Vec3> points;
  std::vector<int> piece;
  two_sheets(0.1, points, piece);
  const Octree tree = data_tree(points);
  const int finest = tree.finest_leaf_level();
  const double gap = 1.2 * finest_side(tree);
  two_sheets(gap, points, piece);
  const Octree near_tree = data_tree(points);
  REQUIRE(near_tree.finest_leaf_level() == finest);

  GapRefinement report;
  const Octree refined = refine_narrow_gaps(near_tree, points, piece, &report);
  CHECK(report.level == finest + 1);
  CHECK(report.narrow_pairs > 0);
  CHECK(report.split_leaves > 0);
  CHECK(refined.finest_leaf_level() == finest + 1);
  // Every point of the gap's mid-plane over the sheets lies in a leaf of the new level; far from the
  // sheets nothing is finer than it was.
  for (double x = -0.45; x <= 0.45; x += 0.05)
    for (double y = -0.45; y <= 0.45; y += 0.05) {
      CHECK(refined.leaf(refined.locate(Vec3(x, y, 0.0))).level == finest + 1);
      const Vec3 far(x, y, 0.9);
      CHECK(refined.leaf_side(refined.locate(far)) == Approx(near_tree.leaf_side(near_tree.locate(far))));
    }
}

TEST_CASE("a wide gap or data in one piece leave the T-mesh as it was", "[gaps]") {
  std::vector<Vec3> points;
  std::vector<int> piece;
  two_sheets(0.1, points, piece);
  const Octree tree = data_tree(points);
  two_sheets(2.5 * finest_side(tree), points, piece);
  const Octree wide = data_tree(points);
  GapRefinement report;
  const Octree same = refine_narrow_gaps(wide, points, piece, &report);
  CHECK(report.narrow_pairs == 0);
  CHECK(report.split_leaves == 0);
  CHECK(same.leaf_count() == wide.leaf_count());
  CHECK(same.max_depth() == wide.max_depth());

  two_sheets(1.2 * finest_side(tree), points, piece);
  const Octree near_tree = data_tree(points);
  const std::vector<int> one_piece(points.size(), 0);
  CHECK(refine_narrow_gaps(near_tree, points, one_piece, &report).leaf_count() == near_tree.leaf_count());
  CHECK(report.split_leaves == 0);
  CHECK_THROWS_AS(refine_narrow_gaps(near_tree, points, std::vector<int>(3, 0)), AlgorithmError);
  CHECK_THROWS_AS(refine_narrow_gaps(near_tree, points, std::vector<int>(points.size(), -1)), AlgorithmError);
}
