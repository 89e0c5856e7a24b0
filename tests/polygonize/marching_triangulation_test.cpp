// What marching triangulation promises beyond every polygonizer's contract (paper §2.2): vertices on
// f = 0 to Newton tolerance, a semi-regular mesh (most vertices of valence 6, no thin triangles),
// edges of about the step, the seven-step seeding, and clear errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <utility>
#include <vector>

#include "algorithms/polygonize/marching_triangulation.hpp"
#include "framework/core/error.hpp"
#include "framework/core/mesh_adjacency.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/polygonize/implicits.hpp"
#include "tests/polygonize/support.hpp"

using namespace dtsl;
using namespace dtsl::test;

namespace {

MarchingTriangulationOptions with_step(double step) {
  MarchingTriangulationOptions o;
  o.step = step;
  return o;
}

double mean_edge_length(const TriangleMesh& m) {
  const MeshEdges edges = mesh_edges(m);
  double sum = 0.0;
  for (const auto& [u, v] : edges.ends) sum += (m.vertices[u] - m.vertices[v]).norm();
  return sum / static_cast<double>(edges.size());
}

}  // namespace

TEST_CASE("marching triangulation is semi-regular with vertices on the surface", "[polygonize][marching_triangulation]") {
  const Sphere sphere(Vec3(0.05, -0.03, 0.02), 0.8);
  const Torus torus(Vec3(0.02, 0.01, -0.03), 0.7, 0.25);
  for (const AnalyticImplicit* shape : {static_cast<const AnalyticImplicit*>(&sphere), static_cast<const AnalyticImplicit*>(&torus)}) {
    const std::vector<Vec3> data = surface_points(*shape, shape->domain(), 1000, 21);
    for (const double step : {0.05, 0.03}) {
      INFO(shape->name() << ", step " << step);
      const MarchingTriangulationOptions options = with_step(step);
      const PolygonizeResult r = marching_triangulation(*shape, data, options);
      const MeshStats st = mesh_stats(r.mesh);
      REQUIRE(st.watertight);
      // Every vertex is a converged Newton projection: |f| / |grad f| below the tolerance.
      double worst = 0.0;
      for (const Vec3& v : r.mesh.vertices) {
        Vec3 g;
        worst = std::max(worst, std::abs(shape->evaluate(v, &g)) / g.norm());
      }
      CHECK(worst < options.newton_tolerance);
      // The paper's semi-regularity claim (docs/design.md §2: most vertices of valence 6), quantified.
      CHECK(st.valence6_fraction >= 0.70);
      CHECK(st.min_angle_p01_deg > 25.0);
      // The step sets the edge length.
      const double mean = mean_edge_length(r.mesh);
      CHECK(mean > 0.85 * step);
      CHECK(mean < 1.15 * step);
      // The summary's quality numbers are the metrics module's.
      CHECK(r.summary.quality.valence6_fraction == Approx(st.valence6_fraction));
      CHECK(r.summary.quality.min_angle_p01_deg == Approx(st.min_angle_p01_deg));
      CHECK(r.summary.quality.min_angle_deg == Approx(st.min_angle_deg));
      CHECK(r.summary.quality.min_angle_mean_deg == Approx(st.min_angle_mean_deg));
      CHECK(r.summary.quality.boundary_edges == 0);
    }
  }
}

TEST_CASE("marching triangulation grows handles by joining fronts", "[polygonize][marching_triangulation]") {
  // A disk-shaped front can only become a surface of genus g by joins (splits and merges): the
  // summary shows them, and the sphere needs none.
  const Sphere sphere(Vec3::Zero(), 0.7);
  const DoubleTorus double_torus;
  const PolygonizeResult s = marching_triangulation(sphere, surface_points(sphere, sphere.domain(), 300, 1), with_step(0.05));
  const PolygonizeResult d =
      marching_triangulation(double_torus, surface_points(double_torus, double_torus.domain(), 300, 1), with_step(0.04));
  CHECK(mesh_stats(d.mesh).genus == Approx(2));
  CHECK(d.summary.details.at("splits").get<int>() + d.summary.details.at("merges").get<int>() >= 2);
  CHECK(s.summary.details.at("merges").get<int>() == 0);
}

TEST_CASE("marching triangulation is deterministic", "[polygonize][marching_triangulation]") {
  const DoubleTorus shape;
  const std::vector<Vec3> data = surface_points(shape, shape.domain(), 500, 4);
  const PolygonizeResult a = marching_triangulation(shape, data, with_step(0.05));
  const PolygonizeResult b = marching_triangulation(shape, data, with_step(0.05));
  REQUIRE(a.mesh.faces.size() == b.mesh.faces.size());
  CHECK(a.mesh.faces == b.mesh.faces);
  CHECK(a.mesh.vertices == b.mesh.vertices);
}

TEST_CASE("marching triangulation seeds from the data's foot points", "[polygonize][marching_triangulation][seeding]") {
  const Sphere sphere(Vec3(0.1, 0.0, 0.0), 0.6);
  SECTION("data off the surface are projected first (seeding step 1)") {
    std::vector<Vec3> data = surface_points(sphere, sphere.domain(), 200, 8);
    for (std::size_t i = 0; i < data.size(); ++i) data[i] += (i % 2 ? 0.05 : -0.05) * (data[i] - Vec3(0.1, 0, 0)).normalized();
    const PolygonizeResult r = marching_triangulation(sphere, data, with_step(0.05));
    CHECK(mesh_stats(r.mesh).components == 1);
    CHECK(r.summary.seed_candidates == data.size());
    CHECK(r.summary.seed_failures == 0);
  }
  SECTION("a component smaller than the step is dropped and counted") {
    const TwoSpheres shape(Vec3(-0.3, 0, 0), 0.6, Vec3(0.9, 0.0, 0.0), 0.01);
    std::vector<Vec3> data = surface_points(shape.first(), shape.domain(), 300, 9);
    data.push_back(Vec3(0.9, 0.0, 0.02));  // a data point on the tiny sphere
    const PolygonizeResult r = marching_triangulation(shape, data, with_step(0.05));
    CHECK(mesh_stats(r.mesh).components == 1);
    CHECK(r.summary.dropped_components >= 1);
  }
  SECTION("no usable seed is an error naming the cause") {
    const Sphere tiny(Vec3::Zero(), 0.01);
    CHECK_THROWS_WITH(marching_triangulation(tiny, {Vec3(0.0, 0.0, 0.02)}, with_step(0.05)), Catch::Contains("step"));
    CHECK_THROWS_AS(marching_triangulation(tiny, {Vec3(0.0, 0.0, 0.02)}, with_step(0.05)), AlgorithmError);
  }
}

TEST_CASE("marching triangulation stops at the domain and caps its work", "[polygonize][marching_triangulation]") {
  SECTION("a level set leaving the domain gives open fronts, no error") {
    const Plane plane;
    const PolygonizeResult r = marching_triangulation(plane, {Vec3(0.1, 0.2, 0.0)}, with_step(0.1));
    CHECK(r.summary.open_boundaries == 1);
    CHECK(mesh_stats(r.mesh).nonmanifold_edges == 0);
  }
  SECTION("a front that cannot close within max_triangles is an error") {
    const Sphere sphere(Vec3::Zero(), 0.8);
    MarchingTriangulationOptions o = with_step(0.05);
    o.max_triangles = 200;
    CHECK_THROWS_WITH(marching_triangulation(sphere, {Vec3(0.8, 0, 0)}, o), Catch::Contains("max_triangles"));
  }
}

TEST_CASE("marching triangulation options check their fields", "[polygonize][marching_triangulation][options]") {
  MarchingTriangulationOptions o;
  CHECK_NOTHROW(o.check());
  o.join_distance = 3.0;
  CHECK_THROWS_WITH(o.check(), Catch::Contains("join_distance"));
  o = MarchingTriangulationOptions();
  o.newton_tolerance = 0.0;
  CHECK_THROWS_WITH(o.check(), Catch::Contains("newton_tolerance"));
  o = MarchingTriangulationOptions();
  o.max_components = 0;
  CHECK_THROWS_AS(o.check(), ConfigError);
}

namespace {

// (x/a)^2 + (y/b)^2 + (z/b)^2 - 1, scaled by b/2 so that |grad f| is about 1 on the sides: a cigar whose
// tips curve with radius b^2 / a, far tighter than its sides (radius b).
class Cigar final : public CentralDifferenceImplicit {
 public:
  Cigar(double a, double b) : a_(a), b_(b) {}

 protected:
  double eval(const Vec3& x, Vec3& g) const override {
    const Vec3 s(1 / (a_ * a_), 1 / (b_ * b_), 1 / (b_ * b_));
    g = b_ * s.cwiseProduct(x);
    return 0.5 * b_ * (x.cwiseProduct(s).dot(x) - 1);
  }

 private:
  double a_, b_;
};

// A torus (radii 0.6 and 0.2) whose tube narrows to radius `neck` around the +x axis over `width` radians.
class NeckedTorus final : public CentralDifferenceImplicit {
 public:
  NeckedTorus(double neck, double width) : neck_(neck), width_(width) {}

 protected:
  double eval(const Vec3& x, Vec3& g) const override {
    const double h = 1e-6;
    for (int a = 0; a < 3; ++a) g[a] = (value(x + h * Vec3::Unit(a)) - value(x - h * Vec3::Unit(a))) / (2 * h);
    return value(x);
  }

 private:
  double value(const Vec3& x) const {
    const double q = std::hypot(x.x(), x.y()), phi = std::atan2(x.y(), x.x());
    const double tube = 0.2 - (0.2 - neck_) * std::exp(-(phi / width_) * (phi / width_));
    return std::hypot(q - 0.6, x.z()) - tube;
  }
  double neck_, width_;
};

}  // namespace

TEST_CASE("marching triangulation's halved steps never cover a thin neck twice",
          "[polygonize][marching_triangulation]") {
  // A neck of radius 0.02 at steps up to 2.5x it: halved steps mesh it (genus 1, the area of one cover)
  // or the march throws; a second sheet grown over the finished mesh (twice the area) must not pass.
  const NeckedTorus torus(0.02, 0.1);
  const std::vector<Vec3> data = surface_points(torus, torus.domain(), 2000, 7);
  const double area = mesh_area(marching_triangulation(torus, data, with_step(0.015)).mesh);
  std::size_t meshed_with_half_steps = 0;
  for (const double step : {0.02, 0.025, 0.03, 0.04, 0.05}) {
    INFO("step " << step);
    try {
      const PolygonizeResult r = marching_triangulation(torus, data, with_step(step));
      CHECK(mesh_area(r.mesh) < 1.05 * area);
      const bool halved = r.summary.details.at("half_steps").get<int>() > 0;
      if (halved && mesh_stats(r.mesh).genus == Approx(1)) ++meshed_with_half_steps;
    } catch (const AlgorithmError& e) {
      CHECK_THAT(e.what(), Catch::Contains("reduce 'step'"));
    }
  }
  CHECK(meshed_with_half_steps > 0);  // steps the neck is too thin for, meshed right at a spot
}

TEST_CASE("marching triangulation takes half steps where one spot is too curved for the step",
          "[polygonize][marching_triangulation]") {
  // Cigars whose tips (radius 0.007-0.016) are far tighter than the steps: where a new point at the step
  // lands too near, too far or turned, one at half (or a quarter, an eighth) of the step takes its place,
  // and the mesh is still closed, of genus 0, on the surface, its edges about the step.
  std::size_t with_half_steps = 0;
  for (const double b : {0.08, 0.1, 0.12}) {
    const Cigar cigar(0.9, b);
    const std::vector<Vec3> data = surface_points(cigar, cigar.domain(), 500, 3);
    for (double step = 0.03; step < 0.062; step += 0.004) {
      INFO("b " << b << ", step " << step);
      const MarchingTriangulationOptions options = with_step(step);
      const PolygonizeResult r = marching_triangulation(cigar, data, options);
      const MeshStats st = mesh_stats(r.mesh);
      CHECK(st.watertight);
      CHECK(st.components == 1);
      CHECK(st.genus == Approx(0));
      double worst = 0.0;
      for (const Vec3& v : r.mesh.vertices) {
        Vec3 g;
        worst = std::max(worst, std::abs(cigar.evaluate(v, &g)) / g.norm());
      }
      CHECK(worst < options.newton_tolerance);
      CHECK(mean_edge_length(r.mesh) > 0.85 * step);
      const int half_steps = r.summary.details.at("half_steps").get<int>();
      CHECK(half_steps <= 0.01 * static_cast<double>(r.mesh.vertices.size()));
      with_half_steps += half_steps > 0;
    }
  }
  CHECK(with_half_steps > 0);  // the sweep reaches spots the full step cannot (in some march, kept or not)
}

TEST_CASE("marching triangulation refuses a step too large for the surface, not only for a spot",
          "[polygonize][marching_triangulation]") {
  // A tube of radius 0.03 at step 0.06: halved steps everywhere would close the tube on itself in a few
  // dozen points (genus 0, exit 0). It must throw, naming the halved step, so that the caller reduces it.
  const Torus torus(Vec3::Zero(), 0.6, 0.03);
  const std::vector<Vec3> data = surface_points(torus, torus.domain(), 500, 3);
  CHECK_THROWS_WITH(marching_triangulation(torus, data, with_step(0.06)),
                    Catch::Contains("needed a halved step") && Catch::Contains("reduce 'step'"));
}
