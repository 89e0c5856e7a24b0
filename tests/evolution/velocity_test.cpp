// The velocity plugins (docs/design.md §1): registered with options and checks, the sign conventions of
// each formula on hand-made samples, and the curvature kappa = div n from a gradient and Hessian.
#include <catch2/catch.hpp>

#include <cmath>

#include "algorithms/evolution/velocity.hpp"
#include "algorithms/tspline/tspline.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"

using namespace dtsl;

namespace {

std::unique_ptr<Velocity> make(const std::string& name) {
  register_velocities();
  return velocities().create(name, "test");
}

/// A zero-set point with outward normal +z, `d` from its nearest data point, which lies along
/// -`toward_data` (grad d = -toward_data... i.e. grad d points from the data point to x).
VelocitySample sample(double d, const Vec3& grad_d, double kappa = 0.0) {
  VelocitySample s;
  s.normal = Vec3::UnitZ();
  s.distance = d;
  s.distance_gradient = grad_d;
  s.curvature = kappa;
  s.cell_size = 0.1;
  return s;
}

}  // namespace

TEST_CASE("velocities: the three plugins are registered with documented, checked options", "[evolution][velocity]") {
  register_velocities();
  for (const char* name : {"distance", "geodesic", "distance_balloon"}) {
    INFO(name);
    REQUIRE(velocities().contains(name));
    auto v = make(name);
    CHECK_NOTHROW(v->options().check());
    CHECK(describe(v->options()).size() >= 1);
    for (const auto& field : describe(v->options())) CHECK(!field.doc.empty());
    auto copy = v->clone();
    CHECK(copy->speed(sample(0.3, Vec3::UnitZ(), 1.0)) == v->speed(sample(0.3, Vec3::UnitZ(), 1.0)));
  }
  auto balloon = make("distance_balloon");
  try {
    apply_assignment(balloon->options(), "beta", "1.5", "velocity");
    FAIL("beta = 1.5 accepted");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()).find("beta") != std::string::npos);
  }
  auto distance = make("distance");
  CHECK_THROWS_AS(apply_assignment(distance->options(), "lambda", "-1", "velocity"), ConfigError);
  CHECK_THROWS_AS(make("no_such_velocity"), ConfigError);
}

TEST_CASE("velocities: signs of the formulas", "[evolution][velocity]") {
  const Vec3 away_outward = Vec3::UnitZ();   // x is outside the data, facing it: grad d . n = +1
  const Vec3 away_inward = -Vec3::UnitZ();   // x has passed the data: grad d . n = -1
  const Vec3 sideways = Vec3::UnitX();       // spanning a concavity: nearest samples to the side

  SECTION("distance: v = -d - lambda kappa, inward everywhere") {
    auto v = make("distance");
    apply_assignment(v->options(), "lambda", "0.01", "velocity");
    CHECK(v->speed(sample(0.5, away_outward)) == Approx(-0.5));
    CHECK(v->speed(sample(0.5, away_inward)) == Approx(-0.5));
    CHECK(v->speed(sample(0.0, Vec3::Zero(), 2.0)) == Approx(-0.02));  // convex parts keep shrinking
  }
  SECTION("geodesic: v = -(grad d . n + lambda d kappa): unit speed far away, jumps sign at the data") {
    auto v = make("geodesic");
    apply_assignment(v->options(), "lambda", "0", "velocity");
    CHECK(v->speed(sample(0.5, away_outward)) == Approx(-1.0));
    CHECK(v->speed(sample(0.001, away_inward)) == Approx(1.0));
    CHECK(v->speed(sample(0.5, sideways)) == Approx(0.0).margin(1e-15));  // stalls over a concavity
    // max_smoothing caps |lambda d kappa|: a thin rim (kappa 40, d 0.05 between samples) is eroded at
    // lambda d kappa = 2 uncapped, at 0.5 capped, so the data's pull (+-1) still holds it.
    apply_assignment(v->options(), "lambda", "1", "velocity");
    apply_assignment(v->options(), "max_smoothing", "1e9", "velocity");
    CHECK(v->speed(sample(0.05, away_inward, 40.0)) == Approx(-1.0));  // 1 - 2: pulled through the data
    apply_assignment(v->options(), "max_smoothing", "0.5", "velocity");
    CHECK(v->speed(sample(0.05, away_inward, 40.0)) == Approx(0.5));    // 1 - 0.5: held at the data
    CHECK(v->speed(sample(0.05, away_inward, -40.0)) == Approx(1.5));   // the cap is symmetric
    CHECK(v->speed(sample(0.05, away_inward, 4.0)) == Approx(0.8));     // below the cap: unchanged
    CHECK_THROWS_AS(apply_assignment(v->options(), "max_smoothing", "-1", "velocity"), ConfigError);
  }
  SECTION("distance_balloon: fast far away, zero on the data, pushes back, reaches into concavities") {
    auto v = make("distance_balloon");
    apply_assignment(v->options(), "beta", "0.2", "velocity");
    apply_assignment(v->options(), "lambda", "0", "velocity");
    CHECK(v->speed(sample(0.5, away_outward)) == Approx(-0.6));   // -(1 + beta) d
    CHECK(v->speed(sample(0.1, away_outward)) == Approx(-0.12));  // proportional to d
    CHECK(v->speed(sample(0.0, Vec3::Zero(), 5.0)) == 0.0);       // at rest on the data
    CHECK(v->speed(sample(0.1, away_inward)) > 0.0);              // overshoot is pushed back out
    CHECK(v->speed(sample(0.3, sideways)) == Approx(-0.06));      // -beta d over a concavity
    apply_assignment(v->options(), "lambda", "0.1", "velocity");
    CHECK(v->speed(sample(0.3, sideways, 2.0)) < v->speed(sample(0.3, sideways, 0.0)));  // convex: smoothed inward
  }
}

TEST_CASE("mean_curvature: div n from the gradient and Hessian", "[evolution][velocity]") {
  // f = |x| - r: grad f = x/|x|, Hessian (I - n n^T)/|x|: kappa = 2/|x|.
  for (double r : {0.25, 0.5, 1.3}) {
    const Vec3 x = r * Vec3(1, 2, -2).normalized();
    const Vec3 n = x.normalized();
    const Mat3 H = (Mat3::Identity() - n * n.transpose()) / r;
    CHECK(mean_curvature(2.0 * n, 2.0 * H) == Approx(2.0 / r));  // invariant under scaling f
    CHECK(mean_curvature(-n, -H) == Approx(-2.0 / r));           // inside-out: concave
  }
  CHECK(mean_curvature(Vec3::UnitZ(), Mat3::Zero()) == 0.0);                  // a plane
  CHECK(mean_curvature(Vec3::Zero(), Mat3::Identity()) == 0.0);               // no normal: 0, not NaN
  // A cylinder of radius r along z: f = sqrt(x^2 + y^2) - r, kappa = 1/r.
  const double r = 0.4;
  const Vec3 n(1, 0, 0);
  Mat3 H = Mat3::Zero();
  H(1, 1) = 1.0 / r;
  CHECK(mean_curvature(n, H) == Approx(1.0 / r));
}

TEST_CASE("mean_curvature of a T-spline quasi-interpolating a sphere's distance", "[evolution][velocity]") {
  auto basis = std::make_shared<TSplineBasis>(uniform_octree(5, 0.25));
  const double r = 0.7;
  const TSpline f = quasi_interpolant(basis, [r](const Vec3& x) { return x.norm() - r; });
  for (const Vec3& dir : {Vec3(1, 0, 0), Vec3(1, 1, 1).normalized(), Vec3(-0.3, 0.8, 0.2).normalized()}) {
    Vec3 g;
    Mat3 H;
    f.evaluate(r * dir, &g, &H);
    CHECK(mean_curvature(g, H) == Approx(2.0 / r).epsilon(0.05));
  }
}
