// The seven-step seeding of paper §2.2 and its distance test, on their own.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "algorithms/polygonize/seeding.hpp"
#include "framework/core/error.hpp"
#include "tests/polygonize/implicits.hpp"

using namespace dtsl;
using namespace dtsl::test;

TEST_CASE("point-triangle distance is the minimum over the triangle", "[polygonize][seeding]") {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0), w(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const Vec3 p(2 * u(rng), 2 * u(rng), 2 * u(rng));
    double brute = 1e300;
    for (int i = 0; i <= 200; ++i)
      for (int j = 0; i + j <= 200; ++j) {
        const double s = i / 200.0, t = j / 200.0;
        brute = std::min(brute, (a + s * (b - a) + t * (c - a) - p).norm());
      }
    const double d = point_triangle_distance(p, a, b, c);
    CHECK(d <= brute + 1e-12);
    CHECK(d >= brute - 0.02 * (b - a).norm() - 0.02 * (c - a).norm());
  }
}

TEST_CASE("mesh_from_seeds starts one march per uncovered component", "[polygonize][seeding]") {
  // Seeds on two clusters; a "march" returns a single triangle around its seed that covers its cluster.
  std::vector<Vec3> seeds;
  for (int i = 0; i < 20; ++i) seeds.emplace_back(0.01 * i, 0, 0);
  for (int i = 0; i < 20; ++i) seeds.emplace_back(1.0 + 0.01 * i, 0, 0);
  seeds.emplace_back(5, 5, 5);  // a seed whose march fails
  int marches = 0;
  const auto march = [&](const Vec3& s) {
    ++marches;
    ComponentMesh c;
    if (s.x() > 4) {
      c.skipped = true;
      return c;
    }
    c.mesh.vertices = {s + Vec3(-0.1, -0.1, 0), s + Vec3(0.5, -0.1, 0), s + Vec3(-0.1, 0.5, 0)};
    c.mesh.normals = {Vec3::UnitZ(), Vec3::UnitZ(), Vec3::UnitZ()};
    c.mesh.faces = {{{0, 1, 2}}};
    return c;
  };
  const SeededMeshing r = mesh_from_seeds(seeds, 0.01, 1.0, 0.1, 10, march);
  CHECK(marches == 3);
  CHECK(r.components == 2);
  CHECK(r.skipped_seeds == 1);
  CHECK(r.mesh.faces.size() == 2);
  CHECK(r.mesh.vertices.size() == 6);
  CHECK(r.mesh.faces[1] == Face{{3, 4, 5}});
  CHECK_THROWS_AS(mesh_from_seeds(seeds, 0.01, 1.0, 0.1, 1, march), AlgorithmError);
}

TEST_CASE("mesh_from_seeds drops a march that meshes a kept component again", "[polygonize][seeding]") {
  // One surface, the unit square z = 0, meshed as a grid of edge h. A seed 0.3 h above it is farther
  // than cover_distance from the first mesh (a tight bend the triangles cut), and its march meshes
  // the same square again. A second square far away is a component of its own.
  const double h = 0.05;
  const auto square = [&](const Vec3& corner) {
    ComponentMesh c;
    const int n = 21;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) c.mesh.vertices.push_back(corner + Vec3(i * h, j * h, 0));
    for (int j = 0; j + 1 < n; ++j)
      for (int i = 0; i + 1 < n; ++i) {
        const int a = j * n + i;
        c.mesh.faces.push_back({{a, a + 1, a + n + 1}});
        c.mesh.faces.push_back({{a, a + n + 1, a + n}});
      }
    return c;
  };
  const std::vector<Vec3> seeds = {Vec3(0.5, 0.5, 0), Vec3(0.52, 0.52, 0.3 * h), Vec3(3.5, 0.5, 0)};
  int marches = 0;
  const auto march = [&](const Vec3& s) {
    ++marches;
    return square(s.x() > 2 ? Vec3(3, 0, 0) : Vec3(0, 0, 0));
  };
  const SeededMeshing r = mesh_from_seeds(seeds, 0.25 * h, 2 * h, 2 * h, 10, march);
  CHECK(marches == 3);
  CHECK(r.components == 2);
  CHECK(r.duplicates == 1);
  CHECK(r.mesh.vertices.size() == 2 * 21 * 21);
}

TEST_CASE("grid seeds find every component crossing the grid", "[polygonize][seeding]") {
  const TwoSpheres shape(Vec3(-0.6, 0.0, 0.0), 0.45, Vec3(0.65, 0.1, 0.0), 0.4);
  const SeedCandidates s = grid_seeds(shape, shape.domain(), 0.1, NewtonOptions());
  REQUIRE(!s.points.empty());
  int first = 0, second = 0;
  for (const Vec3& p : s.points) {
    CHECK(shape.distance(p) < 1e-9);
    first += shape.first().distance(p) < 1e-9;
    second += shape.second().distance(p) < 1e-9;
  }
  CHECK(first > 0);
  CHECK(second > 0);
  CHECK(s.failures == 0);
}
