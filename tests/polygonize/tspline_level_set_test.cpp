// Every polygonizer on a Phase 1 level set: a rational T-spline on an adaptive T-mesh (T-junctions,
// |grad f| != 1) quasi-interpolating a torus and the genus-2 blend of two tori.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "algorithms/polygonize/marching_cubes.hpp"
#include "algorithms/polygonize/polygonizer.hpp"
#include "algorithms/tspline/tspline.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/polygonize/implicits.hpp"
#include "tests/polygonize/support.hpp"
#include "tests/tspline/point_sets.hpp"

using namespace dtsl;
using namespace dtsl::test;

TEST_CASE("every polygonizer meshes a T-spline level set closed, manifold and embedded", "[polygonize][tspline]") {
  register_polygonizers();
  // The adaptive T-mesh of a torus sample 30x denser on one side (levels 3 to 5: T-junctions).
  TMeshOptions tm;
  tm.max_depth = 5;
  tm.points_per_cell = 16;
  const auto basis = std::make_shared<TSplineBasis>(build_octree(nonuniform_torus_points(6000, 0.6, 0.25, 30.0, 7), tm));
  const Torus torus(Vec3::Zero(), 0.6, 0.25);
  const DoubleTorus double_torus;
  struct Case {
    const AnalyticImplicit* source;
    TSpline f;
  };
  const std::vector<Case> cases = {
      {&torus, quasi_interpolant(basis, [&](const Vec3& x) { return torus.value(x); })},
      // The genus-2 blend has a fillet of curvature radius ~0.08: the torus-adapted T-mesh is too coarse
      // there, and the shape reaches |x| = 1.3, past the default domain [-1.25, 1.25]: so it gets the uniform
      // depth-5 grid on [-1.5, 1.5]^3 (the full-octree special case of the same basis).
      {&double_torus, quasi_interpolant(std::make_shared<TSplineBasis>(uniform_octree(5, 0.5)),
                                        [&](const Vec3& x) { return double_torus.value(x); })}};
  for (const Case& c : cases)
    for (const std::string& name : polygonizers().names()) {
      INFO(name << " on the T-spline of " << c.source->name());
      auto p = polygonizers().create(name, "test");
      set_option(p->options(), "step", 0.03);  // about 0.2 l_T for the level-5 cells (paper §2.2)
      const std::vector<Vec3> data = surface_points(c.f, c.f.domain(), 1000, 3);
      const PolygonizeResult r = p->polygonize(c.f, data);
      const MeshStats st = mesh_stats(r.mesh);
      CHECK(st.watertight);
      CHECK(st.components == 1);
      CHECK(st.genus == Approx(c.source->genus()));
      CHECK(self_intersections(r.mesh) == 0);
      double worst = 0.0;  // first-order distance of the vertices to the spline's zero set
      for (const Vec3& v : r.mesh.vertices) {
        Vec3 g;
        worst = std::max(worst, std::abs(c.f.evaluate(v, &g)) / g.norm());
      }
      CHECK(worst < (name == "marching_triangulation" ? 1e-9 : 0.02 * 0.03));
      if (name == "marching_triangulation") {
        CHECK(st.valence6_fraction >= 0.7);
        CHECK(st.min_angle_p01_deg > 25.0);
      }
    }
}

namespace {

/// The same T-spline without its positive certificate: what marching cubes did before it had one.
class Uncertified final : public ImplicitFunction {
 public:
  explicit Uncertified(const ImplicitFunction& f) : f_(f) {}
  double evaluate(const Vec3& x, Vec3* g, Mat3* h) const override { return f_.evaluate(x, g, h); }
  BoundingBox domain() const override { return f_.domain(); }

 private:
  const ImplicitFunction& f_;
};

}  // namespace

TEST_CASE("a T-spline's positive certificate holds only where f > 0, and marching cubes skips samples "
          "without changing a bit of its mesh", "[polygonize][tspline][marching_cubes]") {
  TMeshOptions tm;
  tm.max_depth = 5;
  tm.points_per_cell = 16;
  const auto basis = std::make_shared<TSplineBasis>(build_octree(nonuniform_torus_points(6000, 0.6, 0.25, 30.0, 7), tm));
  const Torus torus(Vec3::Zero(), 0.6, 0.25);
  const TSpline f = quasi_interpolant(basis, [&](const Vec3& x) { return torus.value(x); });
  const auto certified = f.positive_certificate();
  REQUIRE(certified);
  // Never wrong (convex hull property), and not useless: most of the space around a torus is certified.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.4, 1.4);  // past the domain too: clamped as evaluate() does
  int certified_count = 0, positive_count = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vec3 x(u(rng), u(rng), u(rng));
    const double v = f.value(x);
    positive_count += v > 0.0;
    if (certified(x)) {
      ++certified_count;
      INFO("x = " << x.transpose() << ", f = " << v);
      REQUIRE(v > 0.0);
    }
  }
  CHECK(certified_count > positive_count / 2);
  CHECK(!certified(Vec3(std::nan(""), 0.0, 0.0)));
  // The level set moved so that the zero set runs close to grid nodes (kOffZero adjustments) too.
  for (const double shift : {0.0, 1e-4}) {
    std::vector<double> c = f.coefficients();
    for (double& ci : c) ci += shift;
    const TSpline g(basis, c);
    const Uncertified plain(g);
    MarchingCubesOptions o;
    o.step = 0.03;
    const std::vector<Vec3> data = surface_points(g, g.domain(), 500, 3);
    const PolygonizeResult fast = marching_cubes(g, data, o);
    const PolygonizeResult full = marching_cubes(plain, data, o);
    INFO("shift " << shift << ": " << fast.summary.details.dump());
    CHECK(fast.mesh.vertices == full.mesh.vertices);
    CHECK(fast.mesh.faces == full.mesh.faces);
    const auto& grid = fast.summary.details["grid"];
    const long nodes = grid[0].get<long>() * grid[1].get<long>() * grid[2].get<long>();
    CHECK(full.summary.details["samples_evaluated"].get<long>() == nodes);
    CHECK(fast.summary.details["samples_evaluated"].get<long>() < nodes / 2);
  }
}
