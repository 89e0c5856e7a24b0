#include <catch2/catch.hpp>

#include <random>

#include "algorithms/normals/normals.hpp"
#include "framework/core/error.hpp"
#include "framework/core/sampling.hpp"
#include "tests/metrics/message_matcher.hpp"
#include "tests/metrics/shapes.hpp"

using namespace dtsl;

namespace {
// Points uniform on a sphere, with their analytic outward normals.
PointCloud sphere_cloud(std::size_t n, double radius, const Vec3& center, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  PointCloud c;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 u = Vec3(g(rng), g(rng), g(rng)).normalized();
    c.points.push_back(center + radius * u);
    c.normals.push_back(u);
  }
  return c;
}

// Area-uniform samples of a fine torus mesh, with the analytic outward normals of the torus.
PointCloud torus_cloud(std::size_t n, double R, double r, std::uint64_t seed) {
  const TriangleMesh mesh = test::torus(R, r, 120, 48);
  std::mt19937_64 rng(seed);
  PointCloud c;
  for (const SurfaceSample& s : sample_surface(mesh, n, rng)) {
    c.points.push_back(s.point);
    c.normals.push_back(test::torus_normal(R, s.point));
  }
  return c;
}

double outward_fraction(const std::vector<Vec3>& estimated, const std::vector<Vec3>& truth) {
  std::size_t out = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) out += estimated[i].dot(truth[i]) > 0.0 ? 1 : 0;
  return static_cast<double>(out) / truth.size();
}

double mean_abs_cosine(const std::vector<Vec3>& estimated, const std::vector<Vec3>& truth) {
  double sum = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) sum += std::abs(estimated[i].dot(truth[i]));
  return sum / truth.size();
}
}  // namespace

TEST_CASE("estimated normals of a sphere point outward", "[normals]") {
  const PointCloud c = sphere_cloud(3000, 0.8, Vec3(0.1, -0.2, 0.3), 4);
  for (bool jet : {true, false})
    for (int k : {5, 18}) {
      std::size_t unoriented = 99;
      const std::vector<Vec3> n = estimate_oriented_normals(c.points, k, jet, &unoriented);
      REQUIRE(n.size() == c.points.size());
      const double outward = outward_fraction(n, c.normals);
      INFO("jet " << jet << " k " << k << " outward " << outward << " |cos| " << mean_abs_cosine(n, c.normals));
      CHECK(unoriented == 0);
      CHECK(outward >= 0.99);
      CHECK(mean_abs_cosine(n, c.normals) > 0.98);
      for (const Vec3& v : n) REQUIRE(v.norm() == Approx(1.0));
    }
}

TEST_CASE("estimated normals of a torus point outward", "[normals]") {
  const PointCloud c = torus_cloud(6000, 0.7, 0.25, 8);
  for (bool jet : {true, false}) {
    std::size_t unoriented = 99;
    const std::vector<Vec3> n = estimate_oriented_normals(c.points, 18, jet, &unoriented);
    const double outward = outward_fraction(n, c.normals);
    INFO("jet " << jet << " outward " << outward << " |cos| " << mean_abs_cosine(n, c.normals));
    CHECK(unoriented == 0);
    CHECK(outward >= 0.99);
  }
}

TEST_CASE("estimated normals of two separate spheres both point outward", "[normals]") {
  // The neighbour graph has two components; each must get its own seed.
  PointCloud c = sphere_cloud(1500, 0.4, Vec3(-0.5, 0, 0), 1);
  const PointCloud d = sphere_cloud(1500, 0.3, Vec3(0.5, 0, 0.2), 2);
  c.points.insert(c.points.end(), d.points.begin(), d.points.end());
  c.normals.insert(c.normals.end(), d.normals.begin(), d.normals.end());
  std::size_t unoriented = 99;
  const std::vector<Vec3> n = estimate_oriented_normals(c.points, 18, true, &unoriented);
  const double outward = outward_fraction(n, c.normals);
  INFO("outward " << outward << " unoriented " << unoriented);
  CHECK(unoriented == 0);
  CHECK(outward >= 0.99);
}

TEST_CASE("exact duplicate points share one outward normal", "[normals]") {
  // Coincident neighbours used to crash CGAL's jet fit; each distinct position is estimated once.
  PointCloud c = sphere_cloud(1000, 1.0, Vec3::Zero(), 6);
  const std::size_t n = c.points.size();
  for (std::size_t i = 0; i < n; ++i)
    for (int copy = 0; copy < 20; ++copy) c.points.push_back(c.points[i]), c.normals.push_back(c.normals[i]);
  const std::vector<Vec3> normals = estimate_oriented_normals(c.points, 18, true);
  CHECK(outward_fraction(normals, c.normals) >= 0.99);
  for (std::size_t i = n; i < c.points.size(); ++i) REQUIRE(normals[i] == normals[(i - n) / 20]);
}

TEST_CASE("with_normals applies the source rule and names the source used", "[normals]") {
  const PointCloud with = sphere_cloud(500, 1.0, Vec3::Zero(), 3);
  PointCloud without = with;
  without.normals.clear();
  NormalSourceOptions o;
  std::string used;

  o.normals = "auto";
  CHECK(with_normals(with, o, used).normals == with.normals);
  CHECK(used == "ground_truth");
  const PointCloud estimated = with_normals(without, o, used);
  CHECK(used == "jet_mst");
  CHECK(estimated.points == without.points);
  CHECK(outward_fraction(estimated.normals, with.normals) >= 0.99);

  o.normals = "ground_truth";
  CHECK(with_normals(with, o, used).normals == with.normals);
  CHECK(used == "ground_truth");
  used.clear();
  CHECK_THROWS_MATCHES(with_normals(without, o, used), AlgorithmError, test::MessageContains({"ground_truth"}));
  CHECK(used.empty());

  o.normals = "jet_mst";  // estimates even when ground truth exists
  const PointCloud jet = with_normals(with, o, used);
  CHECK(used == "jet_mst");
  CHECK(jet.normals != with.normals);
  o.normals = "pca_mst";
  with_normals(with, o, used);
  CHECK(used == "pca_mst");
}

TEST_CASE("normal options are checked field by field", "[normals][errors]") {
  NormalSourceOptions o;
  CHECK_NOTHROW(o.check());
  o.normals = "viewpoint";
  CHECK_THROWS_MATCHES(o.check(), ConfigError,
                       test::MessageContains({"normals", "viewpoint"}));
  o.normals = "auto";
  o.normal_neighbours = 2;
  CHECK_THROWS_MATCHES(o.check(), ConfigError, test::MessageContains({"normal_neighbours"}));
  o.normal_neighbours = 201;
  CHECK_THROWS_AS(o.check(), ConfigError);
}

TEST_CASE("normal estimation rejects too few or bad points", "[normals][errors]") {
  const PointCloud c = sphere_cloud(18, 1.0, Vec3::Zero(), 5);
  CHECK_THROWS_MATCHES(estimate_oriented_normals(c.points, 18, true), AlgorithmError,
                       test::MessageContains({"18 distinct points", "19"}));
  CHECK_NOTHROW(estimate_oriented_normals(c.points, 17, true));
  CHECK_THROWS_AS(estimate_oriented_normals({Vec3(0, 0, 0), Vec3(1, 0, 0)}, 1, false), AlgorithmError);
  CHECK_THROWS_AS(estimate_oriented_normals({}, 3, true), AlgorithmError);
  CHECK_THROWS_MATCHES(estimate_oriented_normals(std::vector<Vec3>(40, Vec3(1, 2, 3)), 18, true), AlgorithmError,
                       test::MessageContains({"1 distinct points (of 40)"}));
  std::vector<Vec3> nan = c.points;
  nan[4].z() = std::nan("");
  CHECK_THROWS_MATCHES(estimate_oriented_normals(nan, 5, true), AlgorithmError, test::MessageContains({"point 4"}));
  PointCloud few;
  few.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  NormalSourceOptions o;
  std::string used;
  CHECK_THROWS_MATCHES(with_normals(few, o, used), AlgorithmError, test::MessageContains({"too few"}));
}
