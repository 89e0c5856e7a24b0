// Control points and local knot vectors: the ray-casting rule of docs/design.md §1 checked against a
// brute-force reading of the rule over all leaves, and its consequences on the uniform grid.
#include <catch2/catch.hpp>

#include <algorithm>
#include <limits>
#include <set>
#include <tuple>

#include "algorithms/tspline/knots.hpp"
#include "tests/tspline/fixtures.hpp"

using namespace dtsl;

namespace {

/// The rule read literally, over all leaves: from `pos`, the next face along +axis is the smallest
/// upper face of the leaves whose closure touches the ray's line and which contain the ray just
/// beyond pos. (A leaf touches the line if the line's other two coordinates lie in its closed box.)
int next_face_brute_force(const Octree& t, const Int3& v, int axis, int pos, int dir) {
  int best = dir > 0 ? std::numeric_limits<int>::max() : std::numeric_limits<int>::min();
  for (int l = 0; l < t.leaf_count(); ++l) {
    const Octree::Cell& c = t.leaf(l);
    const int s = t.cell_size(c.level);
    bool touches = true;
    for (int a = 0; a < 3; ++a)
      if (a != axis) touches &= c.origin[a] <= v[a] && v[a] <= c.origin[a] + s;
    if (!touches) continue;
    if (dir > 0 && c.origin[axis] <= pos && pos < c.origin[axis] + s) best = std::min(best, c.origin[axis] + s);
    if (dir < 0 && c.origin[axis] < pos && pos <= c.origin[axis] + s) best = std::max(best, c.origin[axis]);
  }
  return best;
}

}  // namespace

TEST_CASE("control points are the leaf vertices, hanging vertices included", "[tspline][knots]") {
  const Octree& t = test::adaptive_basis()->octree();
  const std::vector<Int3> v = control_vertices(t);
  std::set<Int3> set(v.begin(), v.end());
  CHECK(set.size() == v.size());  // no duplicates
  CHECK(std::is_sorted(v.begin(), v.end(), [](const Int3& a, const Int3& b) {
    return std::make_tuple(a[2], a[1], a[0]) < std::make_tuple(b[2], b[1], b[0]);
  }));
  // Every leaf corner is a control point, and every control point is a corner of some leaf.
  std::set<Int3> corners;
  int hanging = 0;
  for (int l = 0; l < t.leaf_count(); ++l) {
    const Octree::Cell& c = t.leaf(l);
    const int s = t.cell_size(c.level);
    for (int o = 0; o < 8; ++o)
      corners.insert({c.origin[0] + ((o & 1) ? s : 0), c.origin[1] + ((o & 2) ? s : 0), c.origin[2] + ((o & 4) ? s : 0)});
  }
  CHECK(corners == set);
  // Hanging vertices: control points strictly inside a face or an edge of some leaf.
  for (int l = 0; l < t.leaf_count(); ++l) {
    const Octree::Cell& c = t.leaf(l);
    const int s = t.cell_size(c.level);
    for (int k = 0; k < 3; ++k) {
      // The midpoint of the leaf's lower face normal to axis k: a hanging vertex if it is a control point.
      Int3 m = c.origin;
      m[(k + 1) % 3] += s / 2;
      m[(k + 2) % 3] += s / 2;
      if (s > 1 && set.count(m)) ++hanging;
    }
  }
  CHECK(hanging > 0);
}

TEST_CASE("local knot vectors follow the ray-casting rule", "[tspline][knots]") {
  for (const auto& [name, basis] : test::all_bases()) {
    SECTION(name) {
      const Octree& t = basis->octree();
      const int R = t.resolution();
      for (int i = 0; i < basis->size(); i += 7) {  // a sample of the control points
        const Int3& v = basis->vertex(i);
        const LocalKnots& k = basis->knots(i);
        for (int a = 0; a < 3; ++a) {
          INFO("control point " << i << " axis " << a);
          CHECK(k[a][2] == v[a]);
          for (int j = 0; j < 4; ++j) CHECK(k[a][j] < k[a][j + 1]);
          // Inside the domain: the next faces met by the ray.
          int pos = v[a];
          for (int j = 3; j <= 4 && pos < R; ++j) {
            CHECK(k[a][j] == next_face_brute_force(t, v, a, pos, +1));
            pos = k[a][j];
          }
          pos = v[a];
          for (int j = 1; j >= 0 && pos > 0; --j) {
            CHECK(k[a][j] == next_face_brute_force(t, v, a, pos, -1));
            pos = k[a][j];
          }
          // Past the boundary: the last interval repeated (for a boundary vertex, the one on the other side).
          if (k[a][4] > R) CHECK(k[a][4] - k[a][3] == k[a][3] - k[a][2]);
          if (k[a][3] > R) CHECK(k[a][3] - k[a][2] == k[a][2] - k[a][1]);
          if (k[a][0] < 0) CHECK(k[a][1] - k[a][0] == k[a][2] - k[a][1]);
          if (k[a][1] < 0) CHECK(k[a][2] - k[a][1] == k[a][3] - k[a][2]);
        }
      }
    }
  }
}

TEST_CASE("on the uniform grid every knot vector is uniform, boundary vertices included", "[tspline][knots]") {
  const Octree t = uniform_octree(3, 0.25);
  for (const Int3& v : control_vertices(t)) {
    const LocalKnots k = local_knots(t, v);
    for (int a = 0; a < 3; ++a)
      for (int j = 0; j < 5; ++j) CHECK(k[a][j] == v[a] - 2 + j);
  }
}
