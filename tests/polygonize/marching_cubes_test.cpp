// What the grid polygonizer promises beyond every polygonizer's contract: its region and vertex
// placement options keep the mesh closed and embedded, and nodes lying on the surface do no harm.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "algorithms/polygonize/marching_cubes.hpp"
#include "framework/core/error.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/polygonize/implicits.hpp"
#include "tests/polygonize/support.hpp"

using namespace dtsl;
using namespace dtsl::test;

TEST_CASE("marching cubes options keep the mesh closed and embedded", "[polygonize][marching_cubes]") {
  const Torus torus(Vec3(0.02, 0.01, -0.03), 0.7, 0.25);
  const std::vector<Vec3> data = surface_points(torus, torus.domain(), 800, 2);
  for (const char* placement : {"linear", "root"})
    for (const bool newton : {false, true})
      for (const char* region : {"domain", "data"}) {
        INFO(placement << (newton ? " + newton" : "") << ", region " << region);
        MarchingCubesOptions o;
        o.step = 0.05;
        o.vertex_placement = placement;
        o.newton_project = newton;
        o.region = region;
        const PolygonizeResult r = marching_cubes(torus, data, o);
        const MeshStats st = mesh_stats(r.mesh);
        CHECK(st.watertight);
        CHECK(st.genus == Approx(1));
        // On their grid edges the vertices cannot make triangles cross; Newton moves them off the
        // edges, and the option documents that tiny triangles near grid nodes may then cross.
        if (!newton) CHECK(self_intersections(r.mesh) == 0);
        double worst = 0.0;
        for (const Vec3& v : r.mesh.vertices) worst = std::max(worst, torus.distance(v));
        if (newton) CHECK(worst < 1e-9);
        // Root placement is exact on the grid edge except within the node margin.
        CHECK(worst < (std::string(placement) == "root" ? 0.02 : 0.1) * o.step);
        const auto grid = r.summary.details.at("grid");
        if (std::string(region) == "data") CHECK(grid[0].get<int>() < 61);
      }
}

TEST_CASE("marching cubes survives grid nodes exactly on the surface", "[polygonize][marching_cubes]") {
  // Radius 0.45 about (-0.6, 0, 0): nodes such as (-0.8, 0.2, -0.35) of the step-0.05 grid lie on it.
  const Sphere sphere(Vec3(-0.6, 0.0, 0.0), 0.45);
  MarchingCubesOptions o;
  o.step = 0.05;
  o.region = "data";
  o.margin = 0.1 + 1e-12;
  for (const char* placement : {"linear", "root"}) {
    INFO(placement);
    o.vertex_placement = placement;
    const PolygonizeResult r = marching_cubes(sphere, surface_points(sphere, sphere.domain(), 400, 3), o);
    const MeshStats st = mesh_stats(r.mesh);
    CHECK(st.watertight);
    CHECK(st.degenerate_faces == 0);
    CHECK(self_intersections(r.mesh) == 0);
  }
}

TEST_CASE("marching cubes drops components without data only when asked", "[polygonize][marching_cubes][seeding]") {
  const TwoSpheres shape(Vec3(-0.6, 0.0, 0.0), 0.45, Vec3(0.65, 0.1, 0.0), 0.4);
  std::vector<Vec3> data;
  for (const Vec3& p : surface_points(shape, shape.domain(), 600, 5))
    if (shape.second().distance(p) < 1e-6) data.push_back(p);
  MarchingCubesOptions o;
  o.step = 0.05;
  const PolygonizeResult kept = marching_cubes(shape, data, o);
  CHECK(mesh_stats(kept.mesh).components == 1);
  CHECK(kept.summary.dropped_components == 1);
  for (const Vec3& v : kept.mesh.vertices) CHECK(shape.second().distance(v) < 0.01);
  o.drop_dataless_components = false;
  const PolygonizeResult all = marching_cubes(shape, data, o);
  CHECK(mesh_stats(all.mesh).components == 2);
  CHECK(all.summary.dropped_components == 0);
}

TEST_CASE("marching cubes reports grids too large and options out of range", "[polygonize][marching_cubes][options]") {
  const Sphere sphere(Vec3::Zero(), 0.5);
  MarchingCubesOptions o;
  o.step = 0.001;
  o.max_grid_nodes = 1'000'000;
  CHECK_THROWS_WITH(marching_cubes(sphere, {}, o), Catch::Contains("max_grid_nodes"));
  o = MarchingCubesOptions();
  o.region = "everywhere";
  CHECK_THROWS_WITH(o.check(), Catch::Contains("region"));
  o = MarchingCubesOptions();
  o.vertex_placement = "cubic";
  CHECK_THROWS_AS(o.check(), ConfigError);
}
