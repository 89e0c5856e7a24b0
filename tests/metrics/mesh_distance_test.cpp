#include <catch2/catch.hpp>

#include <random>
#include <thread>

#include "framework/core/error.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/metrics/brute_force.hpp"
#include "tests/metrics/message_matcher.hpp"
#include "tests/metrics/shapes.hpp"

using namespace dtsl;

namespace {
// A non-convex, irregular mesh: a torus with every vertex jittered.
TriangleMesh jittered_torus(std::uint64_t seed) {
  TriangleMesh m = test::torus(1.0, 0.35, 24, 12);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.04, 0.04);
  for (Vec3& v : m.vertices) v += Vec3(u(rng), u(rng), u(rng));
  return m;
}

std::vector<Vec3> random_points(std::size_t n, double half, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-half, half);
  std::vector<Vec3> p(n);
  for (Vec3& x : p) x = Vec3(u(rng), u(rng), u(rng));
  return p;
}
}  // namespace

TEST_CASE("MeshDistance agrees with a brute-force point-triangle distance over all faces", "[metrics][distance]") {
  for (const TriangleMesh& mesh : {test::icosphere(2), jittered_torus(7), test::tetrahedron()}) {
    const MeshDistance distance(mesh);
    double worst = 0.0;
    for (const Vec3& p : random_points(3000, 1.8, 11)) {
      const MeshDistance::Hit hit = distance.closest(p);
      const double reference = test::brute_force_distance(mesh, p);
      worst = std::max(worst, std::abs(hit.distance - reference));
      // The reported face and point are consistent with the distance.
      REQUIRE(hit.face >= 0);
      REQUIRE(hit.face < static_cast<int>(mesh.faces.size()));
      REQUIRE(test::face_distance(mesh, hit.face, p) == Approx(hit.distance).margin(1e-12));
      REQUIRE((hit.point - p).norm() == Approx(hit.distance).margin(1e-15));
      REQUIRE(test::face_distance(mesh, hit.face, hit.point) < 1e-12);
    }
    CHECK(worst < 1e-12);
  }
}

TEST_CASE("MeshDistance: points on the surface are at distance zero", "[metrics][distance]") {
  const TriangleMesh mesh = test::icosphere(3);
  const MeshDistance distance(mesh);
  for (const Vec3& v : mesh.vertices) CHECK(distance.closest(v).distance < 1e-14);
}

TEST_CASE("MeshDistance: concurrent queries give the sequential answers", "[metrics][distance]") {
  const TriangleMesh mesh = jittered_torus(3);
  const MeshDistance distance(mesh);
  const std::vector<Vec3> points = random_points(4000, 1.5, 5);
  std::vector<double> sequential(points.size()), parallel(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) sequential[i] = distance.closest(points[i]).distance;
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (std::size_t i = t; i < points.size(); i += 4) parallel[i] = distance.closest(points[i]).distance;
    });
  for (std::thread& th : threads) th.join();
  CHECK(parallel == sequential);
}

TEST_CASE("MeshDistance::closest_all answers in input order", "[metrics][distance]") {
  const TriangleMesh mesh = jittered_torus(4);
  const MeshDistance distance(mesh);
  const std::vector<Vec3> points = random_points(3000, 1.5, 6);
  const std::vector<MeshDistance::Hit> hits = distance.closest_all(points);
  REQUIRE(hits.size() == points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const MeshDistance::Hit one = distance.closest(points[i]);
    REQUIRE(hits[i].distance == one.distance);
    REQUIRE(hits[i].face == one.face);
    REQUIRE(hits[i].point == one.point);
  }
  CHECK(distance.closest_all({}).empty());
  CHECK_THROWS_MATCHES(distance.closest_all({Vec3::Zero(), Vec3(0, std::nan(""), 0)}), AlgorithmError,
                       test::MessageContains({"point 1"}));
}

TEST_CASE("MeshDistance: zero-area faces are skipped, the rest still answers", "[metrics][distance]") {
  TriangleMesh mesh = test::tetrahedron();
  mesh.faces.push_back({{0, 0, 1}});                // repeated index
  mesh.vertices.push_back({0.5, 0.0, 0.0});          // collinear with 0 and 1
  mesh.faces.push_back({{0, 4, 1}});
  const MeshDistance distance(mesh);
  const MeshDistance::Hit hit = distance.closest({0.5, -1.0, 0.0});
  CHECK(hit.distance == Approx(1.0));
  CHECK(hit.face < 4);
}

TEST_CASE("MeshDistance rejects unusable meshes", "[metrics][distance][errors]") {
  TriangleMesh no_faces;
  no_faces.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  CHECK_THROWS_MATCHES(MeshDistance(no_faces), AlgorithmError, test::MessageContains({"no faces"}));

  TriangleMesh bad_index = test::tetrahedron();
  bad_index.faces[2][1] = 4;
  CHECK_THROWS_MATCHES(MeshDistance(bad_index), AlgorithmError,
                       test::MessageContains({"face 2", "index 4"}));
  bad_index.faces[2][1] = -1;
  CHECK_THROWS_AS(MeshDistance(bad_index), AlgorithmError);

  TriangleMesh flat;
  flat.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  flat.faces = {{{0, 1, 2}}};
  CHECK_THROWS_MATCHES(MeshDistance(flat), AlgorithmError, test::MessageContains({"zero area"}));

  TriangleMesh nan = test::tetrahedron();
  nan.vertices[3].x() = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_MATCHES(MeshDistance(nan), AlgorithmError, test::MessageContains({"vertex 3"}));
}
