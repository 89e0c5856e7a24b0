// The pieces of the sharpening phase on small hand-made inputs: foot-point cases (Fig. 2, Eq. 6), the
// bilateral target (Eq. 8), the two solver plugins, the degenerate removal.
#include <catch2/catch.hpp>
#include <random>

#include "algorithms/sharpen/bilateral_target.hpp"
#include "algorithms/sharpen/degenerate_removal.hpp"
#include "algorithms/sharpen/foot_points.hpp"
#include "framework/core/error.hpp"
#include "framework/core/mesh_adjacency.hpp"
#include "algorithms/sharpen/sharpen_solver.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/sharpen/block_fixture.hpp"

using namespace dtsl;
using namespace dtsl::sharpen;

namespace {

// Two triangles forming the unit square in z = 0 (normal +z).
TriangleMesh square() {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.faces = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

// A roof: two planes z = -|x| meeting at the ridge x = 0, sampled on a grid of spacing h, with the ridge
// row lowered by `sag` (a rounded edge).
TriangleMesh roof(double h, int n, double sag) {
  TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = (i - n / 2) * h, y = (j - n / 2) * h;
      m.vertices.emplace_back(x, y, -std::abs(x) - (i == n / 2 ? sag : 0.0));
    }
  auto id = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

}  // namespace

TEST_CASE("foot points sort into the three cases of Fig. 2", "[sharpen][foot]") {
  const TriangleMesh m = square();
  const std::vector<Vec3> p = {{0.7, 0.2, 0.3},     // above the inside of face 0: 3 vertices
                               {0.5, 0.5, -0.2},    // above the diagonal (edge 0-2): 2 vertices
                               {1.5, 1.5, 0.1},     // beyond the corner 2: 1 vertex
                               {0.5, -0.4, 0.0}};   // beyond the edge 0-1: 2 vertices
  const auto feet = foot_points(m, p, 1e-6);
  REQUIRE(feet.size() == 4);
  CHECK(feet[0].count == 3);
  CHECK(feet[1].count == 2);
  CHECK(feet[2].count == 1);
  CHECK(feet[2].vertices[0] == 2);
  CHECK(feet[3].count == 2);
  for (const auto& f : feet) {
    Vec3 q = Vec3::Zero();
    double s = 0.0;
    for (int c = 0; c < f.count; ++c) {
      q += f.lambda[c] * m.vertices[f.vertices[c]];
      s += f.lambda[c];
    }
    CHECK(s == Approx(1.0));
    CHECK((q - f.q).norm() < 1e-12);  // Eq. 6: q is the lambda-combination of its vertices
  }
  CHECK(feet[0].distance == Approx(0.3));
  CHECK(mean_distance(feet) == Approx((0.3 + 0.2 + std::sqrt(0.5 + 0.01) + 0.4) / 4));
}

TEST_CASE("the bilateral target keeps a flat vertex and lifts a rounded ridge towards the edge", "[sharpen][bilateral]") {
  const double h = 0.03, sigma = 2 * h;
  {
    TriangleMesh flat = roof(h, 10, 0.0);
    for (auto& v : flat.vertices) v.z() = 0.0;
    const auto adj = mesh_adjacency(flat);
    const int centre = 5 * 11 + 5;
    CHECK((bilateral_target(flat, adj, centre, sigma, sigma, 2 * sigma) - flat.vertices[centre]).norm() < 1e-12);
  }
  const double sag = 0.4 * h;
  const TriangleMesh m = roof(h, 10, sag);
  const auto adj = mesh_adjacency(m);
  const int centre = 5 * 11 + 5;  // on the lowered ridge, x = 0
  const Vec3 target = bilateral_target(m, adj, centre, sigma, sigma, 2 * sigma);
  // Towards the sharp ridge at z = 0 (the two planes' intersection): the sag shrinks, x stays.
  CHECK(target.z() > m.vertices[centre].z() + 0.2 * sag);
  CHECK(std::abs(target.x()) < 1e-9);
}

TEST_CASE("solvers eigen_ldlt and ceres agree on a sparse least-squares problem", "[sharpen][solver]") {
  register_sharpen_solvers();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> pick(0, 199);
  LinearLeastSquares p;
  p.unknowns = 200;
  for (int i = 0; i < 200; ++i) {  // a bilateral-like row per unknown keeps it well posed
    LinearRow r;
    r.count = 1;
    r.unknowns[0] = i;
    r.coeffs[0] = 1.0;
    r.rhs = Vec3(u(rng), u(rng), u(rng));
    r.weight = 0.5;
    p.rows.push_back(r);
  }
  for (int k = 0; k < 600; ++k) {  // data-like rows on 1-3 unknowns with barycentric weights
    LinearRow r;
    r.count = 1 + k % 3;
    double s = 0.0;
    for (int j = 0; j < r.count; ++j) {
      r.unknowns[j] = pick(rng);
      r.coeffs[j] = 0.1 + std::abs(u(rng));
      s += r.coeffs[j];
    }
    for (int j = 0; j < r.count; ++j) r.coeffs[j] /= s;
    r.rhs = Vec3(u(rng), u(rng), u(rng));
    p.rows.push_back(r);
  }
  const Eigen::MatrixX3d a = sharpen_solvers().create("eigen_ldlt", "test")->solve(p);
  const Eigen::MatrixX3d b = sharpen_solvers().create("ceres", "test")->solve(p);
  CHECK((a - b).cwiseAbs().maxCoeff() < 1e-6);  // solutions are O(1)
  // A minimiser: any perturbation raises the objective.
  const double f = objective(p, a);
  Eigen::MatrixX3d d = Eigen::MatrixX3d::Zero(200, 3);
  d(17, 1) = 1e-4;
  CHECK(objective(p, a + d) > f);
  CHECK(objective(p, a - d) > f);
}

TEST_CASE("unknown solver names and bad solver options are config errors", "[sharpen][solver]") {
  register_sharpen_solvers();
  CHECK_THROWS_AS(sharpen_solvers().create("cholmod", "sharpen.solver"), ConfigError);
  auto ceres = sharpen_solvers().create("ceres", "test");
  std::string name = "max_iterations";
  struct SetInt final : FieldVisitor {
    void field(const char*, bool&, const char*) override {}
    void field(const char* n, int& v, const char*) override {
      if (std::string(n) == "max_iterations") v = 0;
    }
    void field(const char*, double&, const char*) override {}
    void field(const char*, std::string&, const char*) override {}
    void field(const char*, std::vector<double>&, const char*) override {}
  } set;
  ceres->options().visit(set);
  CHECK_THROWS_WITH(ceres->options().check(), Catch::Contains("max_iterations"));
}

TEST_CASE("degenerate removal collapses short edges and keeps the mesh closed", "[sharpen][degenerate]") {
  const TriangleMesh start = sharpen_test::rounded_block_mesh(0.06, 0.05);
  const MeshStats before = mesh_stats(start);
  REQUIRE(before.watertight);
  TriangleMesh m = start;
  std::vector<char> all(m.vertices.size(), 1);
  DegenerateRemovalOptions o;
  const auto rep = remove_degenerate_triangles(m, all, o);
  const MeshStats after = mesh_stats(m);
  CHECK(rep.collapsed > 0);
  CHECK(after.watertight);
  CHECK(after.genus == Approx(before.genus));
  CHECK(after.min_angle_p01_deg > before.min_angle_p01_deg);
  CHECK(all.size() == m.vertices.size());
  CHECK(rep.face_origin.size() == m.faces.size());
  // The surface stays where it was.
  CHECK(compare_surfaces(m, start, 20000, 0.005, 1).hausdorff < 0.02);
}

TEST_CASE("foot points updated after some vertices moved equal those found anew", "[sharpen][foot]") {
  const TriangleMesh before = sharpen_test::block_truth();
  std::mt19937_64 rng(7);
  std::normal_distribution<double> offset(0.0, 0.02);
  std::vector<Vec3> points = sharpen_test::block_points(before, 3000, 3);
  for (Vec3& p : points) p += Vec3(offset(rng), offset(rng), offset(rng));
  const std::vector<FootPoint> feet = foot_points(before, points, 1e-6);
  const MeshAdjacency adj = mesh_adjacency(before);
  for (const std::size_t stride : {std::size_t(1), std::size_t(7), before.vertices.size()}) {
    TriangleMesh after = before;  // every stride-th vertex moved (stride = size: one vertex)
    for (std::size_t v = 0; v < after.vertices.size(); v += stride)
      after.vertices[v] += 2.0 * Vec3(offset(rng), offset(rng), offset(rng));
    const std::vector<FootPoint> updated = update_foot_points(before, after, adj.vertex_faces, feet, points, 1e-6);
    const std::vector<FootPoint> anew = foot_points(after, points, 1e-6);
    REQUIRE(updated.size() == anew.size());
    std::size_t changed = 0, differ = 0, misplaced = 0;
    for (std::size_t k = 0; k < anew.size(); ++k) {
      changed += feet[k].distance != anew[k].distance;
      differ += std::abs(updated[k].distance - anew[k].distance) > 1e-12 || (updated[k].q - anew[k].q).norm() > 1e-9;
      // The foot's face and weights are those of the moved mesh: they give back q, on that face.
      const FootPoint& f = updated[k];
      Vec3 q = Vec3::Zero();
      for (int c = 0; c < f.count; ++c) {
        q += f.lambda[c] * after.vertices[f.vertices[c]];
        const Face& t = after.faces[f.face];
        misplaced += std::find(t.begin(), t.end(), f.vertices[c]) == t.end();
      }
      misplaced += (q - f.q).norm() > 1e-5;
    }
    INFO("stride " << stride);
    CHECK(changed > 0);  // the move matters to some points
    CHECK(differ == 0);
    CHECK(misplaced == 0);
  }
  // Unmoved: the same feet. Different faces or sizes: an error.
  CHECK(update_foot_points(before, before, adj.vertex_faces, feet, points, 1e-6).size() == feet.size());
  TriangleMesh other = before;
  std::swap(other.faces[0][0], other.faces[0][1]);
  CHECK_THROWS_AS(update_foot_points(before, other, adj.vertex_faces, feet, points, 1e-6), AlgorithmError);
  CHECK_THROWS_AS(update_foot_points(before, before, adj.vertex_faces, feet, {}, 1e-6), AlgorithmError);
  std::vector<FootPoint> stray = feet;
  stray[0].face = int(before.faces.size());
  CHECK_THROWS_AS(update_foot_points(before, before, adj.vertex_faces, stray, points, 1e-6), AlgorithmError);
}

TEST_CASE("foot points updated on a flat mesh with the data on it (boxes of no volume)", "[sharpen][foot]") {
  const TriangleMesh before = square();
  std::vector<Vec3> points;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j) points.emplace_back(0.1 * i, 0.1 * j, 0.0);
  const std::vector<FootPoint> feet = foot_points(before, points, 1e-6);
  TriangleMesh after = before;
  after.vertices[2] = Vec3(0.9, 1.1, 0.0);  // moved within the plane: every foot distance stays 0 or grows
  const std::vector<FootPoint> updated =
      update_foot_points(before, after, mesh_adjacency(before).vertex_faces, feet, points, 1e-6);
  const std::vector<FootPoint> anew = foot_points(after, points, 1e-6);
  for (std::size_t k = 0; k < points.size(); ++k) CHECK(updated[k].distance == Approx(anew[k].distance).margin(1e-12));
}
