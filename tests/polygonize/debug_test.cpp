#include <catch2/catch.hpp>
#include <cstdio>
#include "algorithms/polygonize/polygonizer.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/polygonize/implicits.hpp"
#include "tests/polygonize/support.hpp"
using namespace dtsl;
using namespace dtsl::test;
TEST_CASE("debug", "[.debug]") {
  register_polygonizers();
  const Sphere shape(Vec3(0.05, -0.03, 0.02), 0.8);
  const std::vector<Vec3> data = surface_points(shape, shape.domain(), 1500, 11);
  const std::vector<Vec3> truth = surface_points(shape, shape.domain(), 4000, 12);
  for (std::string placement : {"root", "linear"}) {
    auto p = polygonizers().create("marching_cubes", "d");
    set_option(p->options(), "step", 0.02);
    struct S final : FieldVisitor { std::string v; void field(const char*, bool&, const char*) override {}
      void field(const char*, int&, const char*) override {} void field(const char*, double&, const char*) override {}
      void field(const char* n, std::string& s, const char*) override { if (std::string(n) == "vertex_placement") s = v; }
      void field(const char*, std::vector<double>&, const char*) override {} } s; s.v = placement;
    p->options().visit(s);
    auto r = p->polygonize(shape, data);
    auto h = hausdorff(r.mesh, shape, truth);
    double vmax = 0; Vec3 w;
    for (auto& v : r.mesh.vertices) if (shape.distance(v) > vmax) { vmax = shape.distance(v); w = v; }
    std::printf("%s: H to %g from %g, vertex max %g at %g %g %g\n", placement.c_str(), h.to_surface, h.from_surface, vmax, w.x(), w.y(), w.z());
  }
}
