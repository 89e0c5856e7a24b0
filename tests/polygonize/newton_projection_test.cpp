// The Newton foot-point projection of paper §3.1 step 3.2, shared by the polygonizers and Phase 2.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "algorithms/polygonize/newton_projection.hpp"
#include "framework/core/error.hpp"
#include "tests/polygonize/implicits.hpp"

using namespace dtsl;
using namespace dtsl::test;

namespace {

/// f = |x|^2 - r^2: the sphere again, but not a distance function (|grad f| = 2|x|), and with a
/// critical point at the centre.
class Quadric final : public ImplicitFunction {
 public:
  explicit Quadric(double r) : r_(r) {}
  double evaluate(const Vec3& x, Vec3* g = nullptr, Mat3* h = nullptr) const override {
    if (g) *g = 2.0 * x;
    if (h) *h = 2.0 * Mat3::Identity();
    return x.squaredNorm() - r_ * r_;
  }
  BoundingBox domain() const override {
    BoundingBox b;
    b.extend(Vec3::Constant(-2));
    b.extend(Vec3::Constant(2));
    return b;
  }

 private:
  double r_;
};

class NotANumber final : public ImplicitFunction {
 public:
  double evaluate(const Vec3&, Vec3* g = nullptr, Mat3* = nullptr) const override {
    if (g) *g = Vec3::UnitX();
    return std::numeric_limits<double>::quiet_NaN();
  }
  BoundingBox domain() const override { return BoundingBox(); }
};

}  // namespace

TEST_CASE("Newton projection lands on f = 0 along the gradient", "[polygonize][newton]") {
  const Quadric f(0.5);
  for (const Vec3& start : {Vec3(1.5, 0.2, -0.3), Vec3(0.1, 0.05, 0.02), Vec3(-0.3, 0.4, 0.5)}) {
    const NewtonProjection r = newton_project(f, start);
    REQUIRE(r.converged());
    CHECK(r.point.norm() == Approx(0.5).margin(1e-10));
    // For a sphere the gradient direction is radial: the foot point keeps the start's direction.
    CHECK(r.point.normalized().dot(start.normalized()) == Approx(1.0).margin(1e-12));
    CHECK(r.normal().dot(r.point.normalized()) == Approx(1.0).margin(1e-12));
    CHECK(std::abs(r.value) / r.gradient.norm() < NewtonOptions().tolerance);
    CHECK(r.iterations <= 10);
  }
  // On a signed distance function one step is exact.
  const Sphere sdf(Vec3(0.1, 0, 0), 0.6);
  const NewtonProjection r = newton_project(sdf, Vec3(1.0, 0.3, 0.2));
  CHECK(r.converged());
  CHECK(r.iterations == 1);
}

TEST_CASE("Newton projection reports failures instead of throwing", "[polygonize][newton]") {
  const Quadric f(0.5);
  CHECK(newton_project(f, Vec3::Zero()).status == NewtonStatus::zero_gradient);
  CHECK(newton_project(NotANumber(), Vec3::Zero()).status == NewtonStatus::not_finite);
  NewtonOptions o;
  o.max_step = 0.1;
  o.max_iterations = 3;
  const NewtonProjection r = newton_project(f, Vec3(1.9, 0, 0), o);
  CHECK(r.status == NewtonStatus::max_iterations);
  CHECK_FALSE(r.converged());
  CHECK(r.point.x() == Approx(1.6));  // three clamped steps of 0.1
  CHECK(std::string(to_string(r.status)) == "max_iterations");
}

TEST_CASE("Newton projection of many points keeps their order", "[polygonize][newton]") {
  const Quadric f(0.5);
  std::vector<Vec3> pts;
  for (int i = 0; i < 1000; ++i) pts.emplace_back(std::cos(i), std::sin(i), 0.01 * i - 5.0);
  const std::vector<NewtonProjection> rs = newton_project_all(f, pts);
  REQUIRE(rs.size() == pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) CHECK(rs[i].point.normalized().dot(pts[i].normalized()) == Approx(1.0));
}

TEST_CASE("Newton options name the field they break", "[polygonize][newton][options]") {
  NewtonOptions o;
  CHECK_NOTHROW(o.check());
  o.tolerance = -1;
  CHECK_THROWS_WITH(o.check("newton_"), Catch::Contains("newton_tolerance"));
  o = NewtonOptions();
  o.max_iterations = 0;
  CHECK_THROWS_AS(o.check(), ConfigError);
}
