// Principal curvatures from grad f and the Hessian; the flipped-face test.
#include <catch2/catch.hpp>

#include "algorithms/displacement/curvature.hpp"
#include "tests/displacement/implicits.hpp"

using namespace dtsl;
using namespace dtsl::test;

TEST_CASE("principal curvatures of analytic implicits", "[displacement][curvature]") {
  const SphereSdf sphere(0.5);
  const PrincipalCurvatures s = principal_curvatures(sphere, Vec3(0.3, 0.4, 0.0));
  REQUIRE(s.valid);
  CHECK(s.k1 == Approx(2.0).epsilon(1e-9));
  CHECK(s.k2 == Approx(2.0).epsilon(1e-9));
  CHECK(s.min_radius() == Approx(0.5).epsilon(1e-9));
  // Ellipsoid (a, b, c) at the tip (a, 0, 0): curvatures a/b^2 and a/c^2 (finite-difference Hessian).
  const Ellipsoid ell(Vec3(0.8, 0.4, 0.2));
  const PrincipalCurvatures e = principal_curvatures(ell, Vec3(0.8, 0, 0));
  CHECK(e.k1 == Approx(0.8 / 0.04).epsilon(1e-5));
  CHECK(e.k2 == Approx(0.8 / 0.16).epsilon(1e-5));
  // The dumbbell's neck (0, n, 0): concave along the axis, k = -2 (k - n^2) / (2 n); convex around it, 1/n.
  const Dumbbell neck(0.08, 1.5);
  const PrincipalCurvatures nk = principal_curvatures(neck, Vec3(0, 0.08, 0));
  CHECK(nk.k1 == Approx(-2 * (1.5 - 0.0064) / 0.16).epsilon(1e-5));
  CHECK(nk.k2 == Approx(1 / 0.08).epsilon(1e-5));
  // A plane: no curvature; a zero gradient: invalid.
  const PrincipalCurvatures p = principal_curvatures(Vec3(0, 0, 1), Mat3::Zero());
  CHECK(p.valid);
  CHECK(std::isinf(p.min_radius()));
  CHECK_FALSE(principal_curvatures(Vec3::Zero(), Mat3::Identity()).valid);
  // A cylinder y^2 + z^2 - r^2: curvatures 1/r and 0.
  const PrincipalCurvatures c = principal_curvatures(Vec3(0, 2 * 0.25, 0), 2.0 * Vec3(0, 1, 1).asDiagonal().toDenseMatrix());
  CHECK(c.k1 == Approx(4.0));
  CHECK(c.k2 == Approx(0.0).margin(1e-12));
}

TEST_CASE("flipped_faces finds reversed and collapsed triangles", "[displacement][curvature]") {
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)};
  m.faces = {Face{0, 1, 2}, Face{1, 3, 2}};
  std::vector<Vec3> after = m.vertices;
  CHECK(flipped_faces(m, after).empty());
  after[2] = Vec3(0, -1, 0.1);  // face 0 reversed; face 1 (1, 3, 2') stays oriented the same way
  const std::vector<int> f = flipped_faces(m, after);
  REQUIRE(f.size() == 1);
  CHECK(f[0] == 0);
  const std::vector<int> only1 = {1};
  CHECK(flipped_faces(m, after, &only1).empty());
  after = m.vertices;
  after[3] = Vec3(0.5, 0.5, 0);  // face 1 collapses onto a segment
  CHECK(flipped_faces(m, after) == std::vector<int>{1});
}
