#include <catch2/catch.hpp>

#include <cmath>

#include "framework/core/error.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/metrics/message_matcher.hpp"
#include "tests/metrics/shapes.hpp"

using namespace dtsl;

TEST_CASE("compare_surfaces of a mesh with itself is zero with F-score 1", "[metrics][surface]") {
  for (const TriangleMesh& mesh : {test::icosphere(3), test::torus(1.0, 0.3, 48, 24)}) {
    const SurfaceMetrics m = compare_surfaces(mesh, mesh, 20000, 0.005, 1);
    CHECK(m.chamfer < 1e-12);
    CHECK(m.hausdorff < 1e-12);
    CHECK(m.precision == 1.0);
    CHECK(m.recall == 1.0);
    CHECK(m.fscore == 1.0);
    CHECK(m.normal_consistency == Approx(1.0).epsilon(0).margin(1e-9));
  }
}

TEST_CASE("compare_surfaces of parallel squares is their exact offset", "[metrics][surface]") {
  // Every sample projects inside the other square, so each distance is exactly the offset h.
  const double h = 0.25;
  const TriangleMesh r = test::rectangle(0, 1, 0, 1, 0.0), g = test::rectangle(0, 1, 0, 1, h);
  const SurfaceMetrics near = compare_surfaces(r, g, 5000, 0.2, 3);  // tau = 0.2 sqrt(2) > h
  CHECK(near.accuracy == Approx(h).epsilon(1e-14));
  CHECK(near.completeness == Approx(h).epsilon(1e-14));
  CHECK(near.chamfer == Approx(h).epsilon(1e-14));
  CHECK(near.hausdorff == Approx(h).epsilon(1e-14));
  CHECK(near.normal_consistency == Approx(1.0).epsilon(1e-14));
  CHECK(near.tau == Approx(0.2 * std::sqrt(2.0)));
  CHECK(near.fscore == 1.0);
  const SurfaceMetrics far = compare_surfaces(r, g, 5000, 0.1, 3);  // tau = 0.141 < h
  CHECK(far.precision == 0.0);
  CHECK(far.recall == 0.0);
  CHECK(far.fscore == 0.0);
}

TEST_CASE("compare_surfaces of a half-covered rectangle matches the analytic values", "[metrics][surface]") {
  // R = [0,1]x[0,1] inside G = [0,2]x[0,1]: accuracy 0; a G sample at x is at distance max(0, x - 1), so
  // completeness = 1/4, hausdorff -> 1, recall = (1 + tau) / 2 with tau = ratio x sqrt(5), precision 1.
  const TriangleMesh r = test::rectangle(0, 1, 0, 1), g = test::rectangle(0, 2, 0, 1);
  const double ratio = 0.05, tau = ratio * std::sqrt(5.0);
  const SurfaceMetrics m = compare_surfaces(r, g, 100000, ratio, 9);
  CHECK(m.accuracy < 1e-14);
  CHECK(m.completeness == Approx(0.25).margin(0.005));  // Monte Carlo: sd about 0.001
  CHECK(m.chamfer == Approx(0.125).margin(0.0025));
  CHECK(m.hausdorff == Approx(1.0).margin(0.001));
  CHECK(m.tau == Approx(tau));
  CHECK(m.precision == 1.0);
  CHECK(m.recall == Approx((1.0 + tau) / 2.0).margin(0.005));
  CHECK(m.fscore == Approx(2 * m.precision * m.recall / (m.precision + m.recall)));
  CHECK(m.normal_consistency == Approx(1.0));
  INFO("completeness " << m.completeness << " recall " << m.recall);
}

TEST_CASE("compare_surfaces of concentric spheres gives the radius difference", "[metrics][surface]") {
  const double r1 = 1.0, r2 = 1.2;
  const TriangleMesh a = test::icosphere(4, r1), b = test::icosphere(4, r2);
  // Polyhedral spheres: each lies between r (1 - s) and r with s = 1 - inradius/r < 0.002 here.
  const double slack = 0.002 * r2;
  const SurfaceMetrics m = compare_surfaces(a, b, 50000, 0.005, 5);
  CHECK(m.chamfer == Approx(r2 - r1).margin(slack));
  CHECK(m.accuracy == Approx(r2 - r1).margin(slack));
  CHECK(m.completeness == Approx(r2 - r1).margin(slack));
  CHECK(m.hausdorff == Approx(r2 - r1).margin(slack));
  CHECK(m.normal_consistency > 0.99);
  CHECK(m.fscore == 0.0);  // tau = 0.005 x diagonal = 0.021 < 0.2
}

TEST_CASE("compare_surfaces is deterministic for a seed", "[metrics][surface]") {
  const TriangleMesh a = test::icosphere(3), b = test::icosphere(2, 1.05);
  const SurfaceMetrics x = compare_surfaces(a, b, 10000, 0.01, 77);
  const SurfaceMetrics y = compare_surfaces(a, b, 10000, 0.01, 77);
  const SurfaceMetrics z = compare_surfaces(a, b, 10000, 0.01, 78);
  CHECK(to_json(x) == to_json(y));
  CHECK(x.chamfer != z.chamfer);
  CHECK(x.chamfer == Approx(z.chamfer).epsilon(0.02));
}

TEST_CASE("compare_surfaces rejects bad input naming the mesh or parameter", "[metrics][surface][errors]") {
  const TriangleMesh good = test::tetrahedron();
  TriangleMesh empty;
  CHECK_THROWS_MATCHES(compare_surfaces(empty, good, 100, 0.005, 1), AlgorithmError,
                       test::MessageContains({"result", "no faces"}));
  CHECK_THROWS_MATCHES(compare_surfaces(good, empty, 100, 0.005, 1), AlgorithmError,
                       test::MessageContains({"truth", "no faces"}));
  TriangleMesh bad = good;
  bad.faces[0][0] = 17;
  CHECK_THROWS_MATCHES(compare_surfaces(bad, good, 100, 0.005, 1), AlgorithmError,
                       test::MessageContains({"result", "17"}));
  CHECK_THROWS_MATCHES(compare_surfaces(good, good, 0, 0.005, 1), AlgorithmError,
                       test::MessageContains({"samples"}));
  CHECK_THROWS_MATCHES(compare_surfaces(good, good, 10, std::nan(""), 1), AlgorithmError,
                       test::MessageContains({"tau_ratio"}));
  CHECK_THROWS_MATCHES(compare_surfaces(good, good, 10, -0.1, 1), AlgorithmError,
                       test::MessageContains({"tau_ratio"}));
}

TEST_CASE("SurfaceMetrics and PointErrors to_json", "[metrics][json]") {
  SurfaceMetrics m;
  m.chamfer = 0.5;
  m.hausdorff = std::nan("");
  const nlohmann::json j = to_json(m);
  CHECK(j.at("chamfer").get<double>() == 0.5);
  CHECK(j.at("hausdorff").is_null());
  for (const char* key : {"accuracy", "completeness", "chamfer", "hausdorff", "normal_consistency", "precision",
                          "recall", "fscore", "tau"})
    CHECK(j.contains(key));
  const nlohmann::json e = to_json(PointErrors{0.001, 0.01});
  CHECK(e.at("e_avr").get<double>() == 0.001);
  CHECK(e.at("e_max").get<double>() == 0.01);
}
