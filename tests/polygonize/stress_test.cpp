// Robustness sweep (hidden: `test_polygonize "[.stress]"`): random rigid motions of the analytic shapes
// and random steps; every run must give a closed, manifold, self-intersection-free mesh of the right
// topology. Prints each failure.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "algorithms/polygonize/polygonizer.hpp"
#include "framework/core/error.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/polygonize/implicits.hpp"
#include "tests/polygonize/support.hpp"

using namespace dtsl;
using namespace dtsl::test;

TEST_CASE("polygonizer robustness sweep", "[.stress]") {
  register_polygonizers();
  // STRESS_SEED / STRESS_TRIALS vary the sweep from the command line.
  const char* seed_env = std::getenv("STRESS_SEED");
  const char* trials_env = std::getenv("STRESS_TRIALS");
  std::mt19937_64 rng(seed_env ? std::strtoull(seed_env, nullptr, 10) : 2024);
  const int trials = trials_env ? std::atoi(trials_env) : 60;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int runs = 0, failures = 0;
  for (int trial = 0; trial < trials; ++trial) {
    std::unique_ptr<AnalyticImplicit> inner;
    bool thin = false;
    switch (trial % 7) {
      case 0: inner = std::make_unique<Sphere>(Vec3::Zero(), 0.5 + 0.4 * u(rng)); break;
      case 1: inner = std::make_unique<Torus>(Vec3::Zero(), 0.55 + 0.2 * u(rng), 0.18 + 0.1 * u(rng)); break;
      case 2: inner = std::make_unique<TwoSpheres>(Vec3(-0.6, 0, 0), 0.3 + 0.15 * u(rng), Vec3(0.6, 0, 0), 0.3 + 0.15 * u(rng)); break;
      case 3: inner = std::make_unique<DoubleTorus>(); break;
      case 4: inner = std::make_unique<BSplineLevelSet>(std::make_unique<Torus>(Vec3::Zero(), 0.55 + 0.2 * u(rng), 0.18 + 0.1 * u(rng)), 0.08 + 0.05 * u(rng)); break;
      case 5: inner = std::make_unique<BSplineLevelSet>(std::make_unique<DoubleTorus>(), 0.08 + 0.05 * u(rng)); break;
      default: inner = std::make_unique<PolynomialDoubleTorus>(); thin = true; break;
    }
    const Eigen::Quaterniond q = Eigen::Quaterniond::UnitRandom();
    const Vec3 t = 0.05 * Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
    const Moved shape(std::move(inner), q.toRotationMatrix(), t);
    const double step = thin ? 0.008 + 0.008 * u(rng) : 0.015 + 0.05 * u(rng);
    const std::vector<Vec3> data = surface_points(shape, shape.domain(), 800, trial);
    for (const std::string& name : polygonizers().names()) {
      ++runs;
      std::string problem;
      try {
        auto p = polygonizers().create(name, "stress");
        set_option(p->options(), "step", step);
        const PolygonizeResult r = p->polygonize(shape, data);
        const MeshStats st = mesh_stats(r.mesh);
        if (!st.watertight) problem += " not-watertight";
        if (st.components != static_cast<std::size_t>(shape.components())) problem += " components=" + std::to_string(st.components);
        if (st.watertight && std::abs(st.genus - shape.genus()) > 0.1) problem += " genus=" + std::to_string(st.genus);
        const std::size_t x = self_intersections(r.mesh);
        if (x) problem += " self-intersections=" + std::to_string(x);
        if (name == "marching_triangulation" && (st.valence6_fraction < 0.7 || st.min_angle_p01_deg < 25))
          problem += " quality v6=" + std::to_string(st.valence6_fraction) + " p01=" + std::to_string(st.min_angle_p01_deg);
      } catch (const Error& e) {
        problem = std::string(" threw: ") + e.what();
      }
      if (!problem.empty()) {
        ++failures;
        std::printf("trial %d %s %s step %.4f:%s\n", trial, name.c_str(), shape.name().c_str(), step, problem.c_str());
      }
    }
  }
  std::printf("%d runs, %d failures\n", runs, failures);
  CHECK(failures == 0);
}

TEST_CASE("polygonizer behaviour at too coarse steps", "[.coarse]") {
  // A step near or above the curvature radius cannot give a faithful mesh; a polygonizer must then
  // either still give a valid closed mesh or throw AlgorithmError, never return a broken one silently.
  register_polygonizers();
  const PolynomialDoubleTorus shape;
  const std::vector<Vec3> data = surface_points(shape, shape.domain(), 500, 1);
  int valid = 0, threw = 0, broken = 0;
  for (const std::string& name : polygonizers().names())
    for (double step = 0.015; step < 0.12; step *= 1.15) {
      try {
        auto p = polygonizers().create(name, "coarse");
        set_option(p->options(), "step", step);
        const PolygonizeResult r = p->polygonize(shape, data);
        const MeshStats st = mesh_stats(r.mesh);
        const std::size_t x = self_intersections(r.mesh);
        const bool ok = st.watertight && x == 0;
        (ok ? valid : broken)++;
        std::printf("%s step %.4f: %s watertight=%d genus=%.1f comps=%zu selfX=%zu\n", name.c_str(), step,
                    ok ? "valid" : "BROKEN", st.watertight, st.genus, st.components, x);
      } catch (const Error& e) {
        ++threw;
        std::printf("%s step %.4f: threw %s\n", name.c_str(), step, e.what());
      }
    }
  std::printf("valid %d, threw %d, broken %d\n", valid, threw, broken);
  CHECK(broken == 0);
}
