// Properties every registered polygonizer must have (docs/design.md §2): on closed analytic level sets of
// genus 0, 1 and 2 and with two components, a closed edge-manifold mesh without self-intersections,
// of the right topology, within a distance of the true surface that shrinks with the step, with
// vertex normals from grad f; data decide which components are meshed, each once.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "algorithms/polygonize/polygonizer.hpp"
#include "framework/core/error.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/polygonize/implicits.hpp"
#include "tests/polygonize/support.hpp"

using namespace dtsl;
using namespace dtsl::test;

namespace {

std::vector<std::unique_ptr<AnalyticImplicit>> closed_shapes() {
  std::vector<std::unique_ptr<AnalyticImplicit>> s;
  // Centres off the grid's symmetry planes so no sample sits exactly on the surface by construction.
  s.push_back(std::make_unique<Sphere>(Vec3(0.05, -0.03, 0.02), 0.8));
  s.push_back(std::make_unique<Torus>(Vec3(0.02, 0.01, -0.03), 0.7, 0.25));
  s.push_back(std::make_unique<TwoSpheres>(Vec3(-0.6, 0.0, 0.0), 0.45, Vec3(0.65, 0.1, 0.0), 0.4));
  s.push_back(std::make_unique<DoubleTorus>());
  // Spline level sets as Phase 1 produces them (C2, |grad f| != 1, cell-wise polynomial).
  s.push_back(std::make_unique<BSplineLevelSet>(std::make_unique<Torus>(Vec3(0.02, 0.01, -0.03), 0.7, 0.25), 0.1));
  s.push_back(std::make_unique<BSplineLevelSet>(std::make_unique<DoubleTorus>(), 0.1));
  return s;
}

std::unique_ptr<Polygonizer> make(const std::string& name, double step) {
  auto p = polygonizers().create(name, "test");
  set_option(p->options(), "step", step);
  return p;
}

// Both methods put vertices on f = 0; the distance to the surface comes from flat triangles over a
// curved surface (sagitta ~ e^2 / 8 rho for edges e ~ step, curvature radius rho >= 0.2 here) and is
// far below this bound, which scales with the step.
constexpr double kHausdorffPerStep = 0.15;

}  // namespace

TEST_CASE("every polygonizer meshes closed level sets closed, manifold and accurate", "[polygonize]") {
  register_polygonizers();
  REQUIRE(polygonizers().names().size() >= 2);
  for (const std::string& name : polygonizers().names()) {
    for (const auto& shape : closed_shapes()) {
      const std::vector<Vec3> data = surface_points(*shape, shape->domain(), 1500, 11);
      const std::vector<Vec3> truth = surface_points(*shape, shape->domain(), 4000, 12);
      for (const double step : {0.045, 0.03}) {
        INFO(name << " on " << shape->name() << ", step " << step);
        const PolygonizeResult r = make(name, step)->polygonize(*shape, data);
        const MeshStats st = mesh_stats(r.mesh);
        CHECK(st.watertight);
        CHECK(st.nonmanifold_edges == 0);
        CHECK(st.nonmanifold_vertices == 0);
        CHECK(st.components == static_cast<std::size_t>(shape->components()));
        CHECK(st.genus == Approx(shape->genus()));
        CHECK(st.degenerate_faces == 0);
        CHECK(self_intersections(r.mesh) == 0);

        const Hausdorff h = hausdorff(r.mesh, *shape, truth);
        INFO("Hausdorff to surface " << h.to_surface << ", from surface " << h.from_surface);
        CHECK(h.value() < kHausdorffPerStep * step);

        // Normals: unit, and grad f / |grad f| at the vertex (not a triangle normal).
        REQUIRE(r.mesh.has_normals());
        double worst = 1.0;
        for (std::size_t v = 0; v < r.mesh.vertices.size(); ++v) {
          CHECK(std::abs(r.mesh.normals[v].norm() - 1.0) < 1e-9);
          worst = std::min(worst, r.mesh.normals[v].dot(shape->gradient(r.mesh.vertices[v]).normalized()));
        }
        CHECK(worst > 1.0 - 1e-9);

        // Outward orientation: the enclosed volume (divergence theorem) is positive.
        double volume = 0.0;
        for (const Face& t : r.mesh.faces)
          volume += r.mesh.vertices[t[0]].dot(r.mesh.vertices[t[1]].cross(r.mesh.vertices[t[2]])) / 6.0;
        CHECK(volume > 0.0);

        CHECK(r.summary.method == name);
        CHECK(r.summary.faces == r.mesh.faces.size());
        CHECK(r.summary.vertices == r.mesh.vertices.size());
        CHECK(r.summary.components == static_cast<std::size_t>(shape->components()));
        CHECK(r.summary.open_boundaries == 0);
        CHECK(r.summary.seconds > 0.0);
        CHECK(to_json(r.summary).at("quality").contains("valence6_fraction"));
      }
    }
  }
}

TEST_CASE("every polygonizer meshes exactly the components that carry data, each once", "[polygonize][seeding]") {
  register_polygonizers();
  const TwoSpheres shape(Vec3(-0.6, 0.0, 0.0), 0.45, Vec3(0.65, 0.1, 0.0), 0.4);
  const std::vector<Vec3> all = surface_points(shape, shape.domain(), 1500, 5);
  std::vector<Vec3> on_first;
  for (const Vec3& p : all)
    if (shape.first().distance(p) < 1e-6) on_first.push_back(p);
  REQUIRE(on_first.size() > 100);
  REQUIRE(on_first.size() < all.size() - 100);
  const double step = 0.04;

  for (const std::string& name : polygonizers().names()) {
    INFO(name);
    SECTION(name + ": data on one sphere -> only that sphere") {
      const PolygonizeResult r = make(name, step)->polygonize(shape, on_first);
      const MeshStats st = mesh_stats(r.mesh);
      CHECK(st.watertight);
      CHECK(st.components == 1);
      for (const Vec3& v : r.mesh.vertices) CHECK(shape.first().distance(v) < 1e-3);
      CHECK(mesh_area(r.mesh) == Approx(shape.first().area()).epsilon(0.02));
    }
    SECTION(name + ": data on both -> both, each once") {
      const PolygonizeResult r = make(name, step)->polygonize(shape, all);
      const MeshStats st = mesh_stats(r.mesh);
      CHECK(st.watertight);
      CHECK(st.components == 2);
      CHECK(r.summary.components == 2);
      // A component meshed twice would double its area.
      CHECK(mesh_area(r.mesh) == Approx(shape.area()).epsilon(0.02));
    }
    SECTION(name + ": no data -> every component") {
      const PolygonizeResult r = make(name, step)->polygonize(shape, {});
      CHECK(mesh_stats(r.mesh).components == 2);
      CHECK(mesh_area(r.mesh) == Approx(shape.area()).epsilon(0.02));
    }
  }
}

TEST_CASE("every polygonizer leaves a level set that crosses the domain open, and says so", "[polygonize]") {
  register_polygonizers();
  const Plane plane;
  const std::vector<Vec3> data = surface_points(plane, plane.domain(), 200, 3);
  for (const std::string& name : polygonizers().names()) {
    INFO(name);
    const PolygonizeResult r = make(name, 0.1)->polygonize(plane, data);
    const MeshStats st = mesh_stats(r.mesh);
    CHECK(st.boundary_edges > 0);
    CHECK(st.nonmanifold_edges == 0);
    CHECK(st.components == 1);
    CHECK(r.summary.open_boundaries >= 1);
    CHECK(r.summary.quality.boundary_edges == st.boundary_edges);
    // It covers the domain's cross-section.
    CHECK(mesh_area(r.mesh) > 0.9 * plane.area());
  }
}

TEST_CASE("polygonizer options are checked and named", "[polygonize][options]") {
  register_polygonizers();
  const Sphere sphere(Vec3::Zero(), 0.5);
  for (const std::string& name : polygonizers().names()) {
    INFO(name);
    auto p = polygonizers().create(name, "test");
    set_option(p->options(), "step", -1.0);
    CHECK_THROWS_AS(p->options().check(), ConfigError);
    CHECK_THROWS_WITH(p->polygonize(sphere, {}), Catch::Contains("step"));
  }
  CHECK_THROWS_AS(polygonizers().create("no_such_polygonizer", "ctx"), ConfigError);
}

TEST_CASE("every polygonizer reports a level set it cannot see", "[polygonize]") {
  register_polygonizers();
  const Sphere outside(Vec3(5, 5, 5), 0.5);  // entirely outside the domain [-1.5, 1.5]^3
  for (const std::string& name : polygonizers().names()) {
    INFO(name);
    CHECK_THROWS_AS(make(name, 0.1)->polygonize(outside, {}), AlgorithmError);
  }
}
