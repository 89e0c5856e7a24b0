// Every stage's mesh is checked before it is handed on (stage_checks.hpp): a planted diverging vertex
// is an error naming the stage and the vertex where nothing can be repaired (MT), and is put back where
// the previous stage had it where the method can (D-Map, B-Evl).
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "algorithms/method/stage_checks.hpp"
#include "framework/core/error.hpp"
#include "tests/metrics/shapes.hpp"

using namespace dtsl;
using Catch::Matchers::Contains;

namespace {

/// A sphere of radius 0.8 and its vertices as the data: every bound is met.
struct Fixture {
  TriangleMesh mesh = test::icosphere(2, 0.8);
  StageBounds bounds = stage_bounds(mesh.vertices);
};

}  // namespace

TEST_CASE("stage bounds: the data's box grown by a quarter of its longest side, moves up to a fifth of its diagonal") {
  const std::vector<Vec3> points = {Vec3(0, 0, 0), Vec3(2, 1, 1)};
  const StageBounds b = stage_bounds(points);
  CHECK(b.box.min.x() == Approx(-0.5));
  CHECK(b.box.max.y() == Approx(1.5));
  CHECK(b.max_move == Approx(0.2 * std::sqrt(6.0)));
  CHECK_THROWS_AS(stage_bounds({}), AlgorithmError);
}

TEST_CASE("a mesh within the bounds passes unchanged") {
  Fixture f;
  const TriangleMesh before = f.mesh;
  TriangleMesh moved = f.mesh;
  for (Vec3& v : moved.vertices) v *= 1.05;  // a small displacement everywhere
  const StageCheck c = check_stage_mesh("D-Map", moved, f.bounds, &before, true);
  CHECK(c.ok());
  CHECK(c.repaired == 0);
  CHECK(c.max_move == Approx(0.04).epsilon(1e-6));
  CHECK(check_stage_mesh("MT", f.mesh, f.bounds).ok());
}

TEST_CASE("a planted diverging vertex of a created mesh is an error naming the stage and the vertex") {
  Fixture f;
  f.mesh.vertices[7] = Vec3(300, 0, 0);
  CHECK_THROWS_WITH(check_stage_mesh("MT", f.mesh, f.bounds),
                    Contains("stage MT diverged") && Contains("vertex 7") && Contains("outside the data's box"));
  Fixture g;
  g.mesh.vertices[3].y() = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(check_stage_mesh("MT", g.mesh, g.bounds), Contains("vertex 3") && Contains("not finite"));
}

TEST_CASE("a vertex a moving stage sends out of bounds goes back to where the previous stage had it") {
  Fixture f;
  const TriangleMesh before = f.mesh;
  TriangleMesh after = f.mesh;
  after.vertices[5] = Vec3(0, 0, -250);                                 // far outside the box
  after.vertices[9] += 0.9 * (after.vertices[9].normalized());          // inside the box, moved too far
  after.vertices[11].x() = std::numeric_limits<double>::infinity();    // not finite
  const StageCheck c = check_stage_mesh("B-Evl", after, f.bounds, &before, true);
  CHECK(c.outside >= 1);
  CHECK(c.moved_too_far >= 1);
  CHECK(c.non_finite == 1);
  CHECK(c.repaired == 3);
  for (int i : {5, 9, 11}) CHECK(after.vertices[i] == before.vertices[i]);
  // Without repair the same mesh is an error.
  TriangleMesh again = f.mesh;
  again.vertices[5] = Vec3(0, 0, -250);
  CHECK_THROWS_WITH(check_stage_mesh("D-Map", again, f.bounds, &before, false), Contains("stage D-Map diverged"));
  // A mesh that is not the moved one is a programming error, named.
  TriangleMesh fewer = f.mesh;
  fewer.vertices.pop_back();
  CHECK_THROWS_WITH(check_stage_mesh("D-Map", fewer, f.bounds, &before, true), Contains("vertices"));
}

TEST_CASE("a moving stage that also remeshes is replaced by the previous mesh when it breaks the bounds") {
  Fixture f;
  const TriangleMesh before = f.mesh;
  TriangleMesh remeshed = test::icosphere(1, 0.8);  // other vertices than `before`
  const StageCheck fine = check_moving_stage("B-Evl", remeshed, f.bounds, before);
  CHECK(fine.ok());
  CHECK_FALSE(fine.replaced);
  CHECK(remeshed.vertices.size() != before.vertices.size());
  remeshed.vertices[2] = Vec3(0, 400, 0);
  const StageCheck broken = check_moving_stage("B-Evl", remeshed, f.bounds, before);
  CHECK(broken.replaced);
  CHECK(broken.outside == 1);
  CHECK(remeshed.vertices == before.vertices);
  // Same vertices: repaired one by one instead.
  TriangleMesh moved = before;
  moved.vertices[4] = Vec3(0, 400, 0);
  const StageCheck repaired = check_moving_stage("D-Map", moved, f.bounds, before);
  CHECK_FALSE(repaired.replaced);
  CHECK(repaired.repaired == 1);
  CHECK(moved.vertices[4] == before.vertices[4]);
}
