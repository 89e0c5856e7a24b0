// The quality and speed numbers quoted in the polygonizer notes (hidden: run with `test_polygonize
// "[.report]"` or `"[.bench]"`). Each also asserts what it measures: every mesh in the report closed,
// with the shape's components and genus, within a marching step of the surface and free of
// self-intersections; every timed mesh non-empty and its time positive.
#include <catch2/catch.hpp>

#include <cstdio>
#include <memory>
#include <vector>

#include "algorithms/polygonize/polygonizer.hpp"
#include "framework/core/timer.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/polygonize/implicits.hpp"
#include "tests/polygonize/support.hpp"

using namespace dtsl;
using namespace dtsl::test;

namespace {

std::vector<std::unique_ptr<AnalyticImplicit>> report_shapes() {
  std::vector<std::unique_ptr<AnalyticImplicit>> s;
  s.push_back(std::make_unique<Sphere>(Vec3(0.05, -0.03, 0.02), 0.8));
  s.push_back(std::make_unique<Torus>(Vec3(0.02, 0.01, -0.03), 0.7, 0.25));
  s.push_back(std::make_unique<TwoSpheres>(Vec3(-0.6, 0.0, 0.0), 0.45, Vec3(0.65, 0.1, 0.0), 0.4));
  s.push_back(std::make_unique<DoubleTorus>());
  return s;
}

}  // namespace

TEST_CASE("polygonizer quality report", "[.report]") {
  register_polygonizers();
  std::printf("%-24s %-13s %6s %8s %7s %6s %6s %6s %6s %9s %9s %5s %4s\n", "method", "shape", "step", "faces", "sec",
              "val6", "minA", "p01", "meanA", "H/step", "H/step^2", "selfX", "g");
  for (const std::string& name : polygonizers().names())
    for (const auto& shape : report_shapes()) {
      const std::vector<Vec3> data = surface_points(*shape, shape->domain(), 1500, 11);
      const std::vector<Vec3> truth = surface_points(*shape, shape->domain(), 4000, 12);
      for (const double step : {0.05, 0.035, 0.02}) {
        auto p = polygonizers().create(name, "report");
        set_option(p->options(), "step", step);
        const PolygonizeResult r = p->polygonize(*shape, data);
        const MeshStats st = mesh_stats(r.mesh);
        const Hausdorff h = hausdorff(r.mesh, *shape, truth);
        std::printf("%-24s %-13s %6.3f %8zu %7.3f %6.3f %6.1f %6.1f %6.1f %9.4f %9.3f %5zu %4.1f\n", name.c_str(),
                    shape->name().c_str(), step, st.faces, r.summary.seconds, st.valence6_fraction, st.min_angle_deg,
                    st.min_angle_p01_deg, st.min_angle_mean_deg, h.value() / step, h.value() / (step * step),
                    self_intersections(r.mesh), st.genus);
        std::printf("    %s\n", to_json(r.summary).at("details").dump().c_str());
        INFO(name << " on " << shape->name() << " at step " << step);
        CHECK(st.watertight);
        CHECK(st.components == (shape->name() == "two_spheres" ? 2u : 1u));
        CHECK(st.genus == Approx(shape->genus()));
        CHECK(h.value() < step);
        CHECK(self_intersections(r.mesh) == 0u);
        CHECK(st.min_angle_deg > 0.0);
      }
    }
}

TEST_CASE("polygonizer speed", "[.bench]") {
  register_polygonizers();
  const Sphere sphere(Vec3(0.05, -0.03, 0.02), 0.8);
  const Torus torus(Vec3(0.02, 0.01, -0.03), 0.7, 0.25);
  for (const std::string& name : polygonizers().names())
    for (const AnalyticImplicit* shape : {static_cast<const AnalyticImplicit*>(&sphere), static_cast<const AnalyticImplicit*>(&torus)}) {
      const std::vector<Vec3> data = surface_points(*shape, shape->domain(), 5000, 3);
      auto p = polygonizers().create(name, "bench");
      set_option(p->options(), "step", 0.02);
      double best = 1e300;
      PolygonizeResult r;
      for (int rep = 0; rep < 3; ++rep) {
        r = p->polygonize(*shape, data);
        best = std::min(best, r.summary.seconds);
      }
      std::printf("%-24s %-8s step 0.02: %8zu triangles in %.3f s = %.0f triangles/s\n", name.c_str(),
                  shape->name().c_str(), r.mesh.faces.size(), best, r.mesh.faces.size() / best);
      INFO(name << " on " << shape->name());
      CHECK(mesh_stats(r.mesh).watertight);
      CHECK(best > 0.0);
    }
}
