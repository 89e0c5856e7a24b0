#include <catch2/catch.hpp>

#include <random>

#include "framework/core/error.hpp"
#include "framework/core/sampling.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/metrics/message_matcher.hpp"
#include "tests/metrics/shapes.hpp"

using namespace dtsl;

TEST_CASE("point_errors equals the exact distances to a convex polyhedron", "[metrics][point_errors]") {
  // Independent computation: for a convex polyhedron, a point c + h n (c inside face f, n its outward
  // normal, h > 0) is at distance exactly h, and an inside point is at the distance of the nearest face
  // plane.
  const TriangleMesh mesh = test::icosphere(2);
  const int faces = static_cast<int>(mesh.faces.size());
  for (int f = 0; f < faces; ++f)  // the precondition: convex
    for (const Vec3& v : mesh.vertices)
      REQUIRE(face_normal(mesh, f).dot(v - mesh.vertices[mesh.faces[f][0]]) < 1e-12);

  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> points;
  std::vector<double> expected;
  for (int i = 0; i < 2000; ++i) {
    const int f = static_cast<int>(u(rng) * faces) % faces;
    const Face& t = mesh.faces[f];
    double a = u(rng), b = u(rng);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    const Vec3 c = mesh.vertices[t[0]] + a * (mesh.vertices[t[1]] - mesh.vertices[t[0]]) +
                   b * (mesh.vertices[t[2]] - mesh.vertices[t[0]]);
    const double h = -0.1 + 0.5 * u(rng);
    const Vec3 p = c + h * face_normal(mesh, f);
    double d = h;
    if (h < 0) {
      d = std::numeric_limits<double>::infinity();
      for (int g = 0; g < faces; ++g)
        d = std::min(d, face_normal(mesh, g).dot(mesh.vertices[mesh.faces[g][0]] - p));
    }
    points.push_back(p);
    expected.push_back(d);
  }
  double sum = 0, max = 0;
  for (double d : expected) sum += d, max = std::max(max, d);
  const PointErrors e = point_errors(points, mesh);
  CHECK(e.e_avr == Approx(sum / expected.size()).epsilon(0).margin(1e-13));
  CHECK(e.e_max == Approx(max).epsilon(0).margin(1e-13));
  INFO("e_avr " << e.e_avr << " e_max " << e.e_max);
}

TEST_CASE("point_errors of points at known radii from a sphere mesh", "[metrics][point_errors]") {
  // The mesh lies between its inradius rho and 1, so each distance is within 1 - rho of |r - 1|.
  const TriangleMesh mesh = test::icosphere(4);
  double rho = 1.0;
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f)
    rho = std::min(rho, face_normal(mesh, f).dot(mesh.vertices[mesh.faces[f][0]]));
  REQUIRE(rho > 0.998);

  std::mt19937_64 rng(1);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> radius(0.5, 1.5);
  std::vector<Vec3> points;
  double sum = 0, max = 0;
  for (int i = 0; i < 5000; ++i) {
    const double r = radius(rng);
    points.push_back(r * Vec3(g(rng), g(rng), g(rng)).normalized());
    sum += std::abs(r - 1.0);
    max = std::max(max, std::abs(r - 1.0));
  }
  const PointErrors e = point_errors(points, mesh);
  CHECK(std::abs(e.e_avr - sum / points.size()) <= 1.0 - rho);
  CHECK(std::abs(e.e_max - max) <= 1.0 - rho);
  CHECK(e.e_avr == Approx(0.25).margin(0.01));  // E|r - 1| for r uniform in [0.5, 1.5]
}

TEST_CASE("point_errors rejects bad input", "[metrics][point_errors][errors]") {
  const TriangleMesh mesh = test::tetrahedron();
  CHECK_THROWS_MATCHES(point_errors({}, mesh), AlgorithmError, test::MessageContains({"no points"}));
  CHECK_THROWS_MATCHES(point_errors({Vec3(0, 0, std::nan(""))}, mesh), AlgorithmError,
                       test::MessageContains({"point 0"}));
  TriangleMesh empty;
  CHECK_THROWS_MATCHES(point_errors({Vec3::Zero()}, empty), AlgorithmError, test::MessageContains({"no faces"}));
}
