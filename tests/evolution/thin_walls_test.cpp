// Thin walls (thin_walls.hpp): found between two faces that face away from each other and are close,
// not on a single face or across a thick part; their rows come only where the middle rose too high.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

#include "algorithms/evolution/thin_walls.hpp"
#include "algorithms/tspline/octree.hpp"

using namespace dtsl;

namespace {

/// A slab |z| <= half_thickness around z = shift, as a level set that wraps both faces from outside:
/// f = |z - shift| - half_thickness - offset (negative inside), the start's orientation of the data.
class Slab final : public ImplicitFunction {
 public:
  Slab(double half_thickness, double offset, double shift = 0.0)
      : half_(half_thickness), offset_(offset), shift_(shift) {}
  double evaluate(const Vec3& x, Vec3* gradient, Mat3* hessian) const override {
    const double z = x.z() - shift_;
    if (gradient) *gradient = Vec3(0.0, 0.0, z >= 0.0 ? 1.0 : -1.0);
    if (hessian) hessian->setZero();
    return std::abs(z) - half_ - offset_;
  }
  BoundingBox domain() const override {
    BoundingBox b;
    b.min = Vec3::Constant(-2.0);
    b.max = Vec3::Constant(2.0);
    return b;
  }

 private:
  double half_, offset_, shift_;
};

/// Both faces of the slab, a grid of `spacing` over [-0.5, 0.5]^2.
std::vector<Vec3> slab_faces(double half_thickness, double spacing) {
  std::vector<Vec3> points;
  const int n = int(std::lround(1.0 / spacing));
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (const double z : {-half_thickness, half_thickness})
        points.emplace_back(-0.5 + i * spacing, -0.5 + j * spacing, z);
  return points;
}

/// A uniform T-mesh at `level` over the default domain.
Octree uniform_tmesh(const std::vector<Vec3>& points, int level) {
  TMeshOptions o;
  o.max_depth = level;
  o.min_depth = level;
  return build_octree(points, o);
}

}  // namespace

TEST_CASE("a slab thinner than a few cells is a wall: middles between its faces, a quarter of its thickness deep",
          "[thin_walls]") {
  const double half = 0.05;  // 0.1 thick: 1.3 cells of level 5 (side 2.5 / 32)
  const std::vector<Vec3> points = slab_faces(half, 0.025);
  const DataDistance data(points);
  const Octree tmesh = uniform_tmesh(points, 5);
  const ThinWalls walls = thin_walls(points, data, Slab(half, 0.01), tmesh);
  REQUIRE(walls.size() == points.size());  // every point has the other face right behind it
  for (std::size_t m = 0; m < walls.size(); ++m) {
    CHECK(std::abs(walls.middle[m].z()) < 1e-12);
    CHECK(walls.depth[m] == Approx(0.25 * 2.0 * half));
  }
}

TEST_CASE("a part thicker than the search, or two faces facing the same way, have no walls", "[thin_walls]") {
  const Octree tmesh = uniform_tmesh(slab_faces(0.05, 0.025), 5);  // leaf side 0.078: search to 0.31
  const std::vector<Vec3> thick = slab_faces(0.25, 0.025);            // 0.5 thick
  CHECK(thin_walls(thick, DataDistance(thick), Slab(0.25, 0.01), tmesh).empty());

  // Two faces that face the same way (a start that wraps them as one side of a thick part) are no wall.
  const std::vector<Vec3> points = slab_faces(0.05, 0.025);
  CHECK(thin_walls(points, DataDistance(points), Slab(0.0, 0.2, 1.0), tmesh).empty());
}

TEST_CASE("the other face must lie behind: within 45 degrees of the inward normal", "[thin_walls]") {
  const Octree tmesh = uniform_tmesh(slab_faces(0.05, 0.025), 5);
  const Slab slab(0.05, 0.01);
  // p on the upper face, q on the lower one 0.1 below and 0.08 aside: 39 degrees off the inward normal.
  const std::vector<Vec3> within = {Vec3(0.0, 0.0, 0.05), Vec3(0.08, 0.0, -0.05)};
  const ThinWalls walls = thin_walls(within, DataDistance(within), slab, tmesh);
  REQUIRE(walls.size() == 2);  // each finds the other
  CHECK(walls.middle[0].isApprox(Vec3(0.04, 0.0, 0.0)));
  CHECK(walls.depth[0] == Approx(0.25 * std::hypot(0.08, 0.1)));
  // 0.12 aside: 50 degrees off, not behind p.
  const std::vector<Vec3> aside = {Vec3(0.0, 0.0, 0.05), Vec3(0.12, 0.0, -0.05)};
  CHECK(thin_walls(aside, DataDistance(aside), slab, tmesh).empty());
}

namespace {
/// A start given by its normals at the data points: the gradient at x is the normal of the nearest one.
class PointNormals final : public ImplicitFunction {
 public:
  PointNormals(std::vector<Vec3> points, std::vector<Vec3> normals)
      : points_(std::move(points)), normals_(std::move(normals)) {}
  double evaluate(const Vec3& x, Vec3* g, Mat3* h) const override {
    std::size_t nearest = 0;
    for (std::size_t k = 1; k < points_.size(); ++k)
      if ((points_[k] - x).norm() < (points_[nearest] - x).norm()) nearest = k;
    if (g) *g = normals_[nearest];
    if (h) h->setZero();
    return 0.0;
  }
  BoundingBox domain() const override { return BoundingBox{Vec3::Constant(-2.0), Vec3::Constant(2.0)}; }

 private:
  std::vector<Vec3> points_, normals_;
};

ThinWalls walls_of(const std::vector<Vec3>& points, const std::vector<Vec3>& normals) {
  const Octree tmesh = uniform_tmesh(slab_faces(0.05, 0.025), 5);  // leaf 0.078, search to 0.31
  return thin_walls(points, DataDistance(points), PointNormals(points, normals), tmesh);
}
}  // namespace

TEST_CASE("a march that leaves the part through a face turned sideways finds no wall beyond it",
          "[thin_walls]") {
  // p faces up, q 0.3 below faces down: a wall, found from both.
  const Vec3 p(0.0, 0.0, 0.1), r(0.0, 0.0, -0.05), q(0.0, 0.0, -0.2);
  CHECK(walls_of({p, q}, {Vec3::UnitZ(), -Vec3::UnitZ()}).size() == 2);
  // Between them, on the march's path, a face the start sees sideways (a concave corner the start
  // spans), 0.15 from each: the march from either end passes through it and ends there. No wall.
  CHECK(walls_of({p, r, q}, {Vec3::UnitZ(), Vec3::UnitX(), -Vec3::UnitZ()}).empty());
  // The same face passed 0.05 aside (more than half a leaf of 0.078) is not on the path: the wall stays.
  const Vec3 aside(0.05, 0.0, -0.05);
  const ThinWalls bar = walls_of({p, aside, q}, {Vec3::UnitZ(), Vec3::UnitX(), -Vec3::UnitZ()});
  REQUIRE(bar.size() == 2);
  CHECK(bar.middle[0].isApprox(0.5 * (p + q)));
}

TEST_CASE("a far face with tilted normals is searched one leaf past where the march meets it",
          "[thin_walls]") {
  // r is met first, turned partly away (n_p . n_r = -0.4); q faces away 0.04 past it: p's wall is q.
  const Vec3 p(0.0, 0.0, 0.05), r(0.0, 0.0, -0.05);
  const Vec3 tilted(std::sqrt(1.0 - 0.16), 0.0, -0.4);
  const ThinWalls near = walls_of({p, r, Vec3(0.0, 0.0, -0.09)}, {Vec3::UnitZ(), tilted, -Vec3::UnitZ()});
  REQUIRE_FALSE(near.empty());
  CHECK(near.middle[0].isApprox(Vec3(0.0, 0.0, -0.02)));
  // 0.15 past it (more than the leaf of 0.078): beyond the face it passed through, no wall for p (and
  // none for the far point, whose march meets r turned sideways to it: n_q . n_r = 0.4).
  const ThinWalls far = walls_of({p, r, Vec3(0.0, 0.0, -0.2)}, {Vec3::UnitZ(), tilted, -Vec3::UnitZ()});
  CHECK(far.empty());
  // The limit holds while the march meets points it skips (s, 49 degrees off -n_p, outside the cone).
  const std::vector<Vec3> skipped = {p, Vec3(0.0, 0.0, 0.03), Vec3(0.035, 0.0, 0.02), Vec3(0.0, 0.0, -0.2)};
  const ThinWalls beyond = walls_of(skipped, {Vec3::UnitZ(), tilted, Vec3::UnitX(), -Vec3::UnitZ()});
  const auto p_to_far = [](const Vec3& w) { return w.isApprox(Vec3(0.0, 0.0, -0.075)); };
  CHECK(std::none_of(beyond.middle.begin(), beyond.middle.end(), p_to_far));
}

TEST_CASE("a wall's row comes only where its middle has risen above the depth", "[thin_walls]") {
  ThinWalls walls;
  walls.middle = {Vec3(0.0, 0.0, 0.0), Vec3(0.3, 0.0, 0.0)};
  walls.depth = {0.02, 0.02};
  // f = |z| - 0.03 + 0.1 x: -0.03 at the first middle (deep enough), -0.0 at the second (risen).
  class Tilted final : public ImplicitFunction {
   public:
    double evaluate(const Vec3& x, Vec3* g, Mat3* h) const override {
      if (g) *g = Vec3(0.1, 0.0, x.z() >= 0.0 ? 1.0 : -1.0);
      if (h) h->setZero();
      return std::abs(x.z()) - 0.03 + 0.1 * x.x();
    }
    BoundingBox domain() const override { return BoundingBox{Vec3::Constant(-2.0), Vec3::Constant(2.0)}; }
  } f;
  const WallRows rows = wall_rows(walls, f, 0.5);
  REQUIRE(rows.position.size() == 1);
  CHECK(rows.position[0].x() == Approx(0.3));
  CHECK(rows.target[0] == Approx((-0.02 - 0.0) / 0.5).margin(1e-12));
}
