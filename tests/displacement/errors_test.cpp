// Bad input and bad options give clear errors naming the problem or the field.
#include <catch2/catch.hpp>
#include <limits>

#include "algorithms/displacement/displacement.hpp"
#include "algorithms/displacement/hole_treatment.hpp"
#include "framework/core/error.hpp"
#include "tests/displacement/implicits.hpp"
#include "tests/displacement/support.hpp"

using namespace dtsl;
using namespace dtsl::test;
using Catch::Matchers::Contains;

// The type and the message of an exception.
#define CHECK_THROWS_MATCHES_TEXT(expr, type, matcher) \
  do {                                                 \
    CHECK_THROWS_AS(expr, type);                       \
    CHECK_THROWS_WITH(expr, matcher);                  \
  } while (0)

TEST_CASE("displacement: bad input throws AlgorithmError naming the problem", "[displacement][errors]") {
  const SphereSdf f(0.6);
  const TriangleMesh base = base_mesh(f, Vec3(0.6, 0, 0), 0.08);
  CHECK_THROWS_MATCHES_TEXT(displace_mesh(f, base, {}), AlgorithmError, Contains("no data points"));
  const std::vector<Vec3> nan_points = {Vec3(0.7, 0, 0), Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0)};
  CHECK_THROWS_MATCHES_TEXT(displace_mesh(f, base, nan_points), AlgorithmError, Contains("data point 1 is not finite"));
  CHECK_THROWS_MATCHES_TEXT(displace_mesh(f, TriangleMesh{}, {Vec3(0.7, 0, 0)}), AlgorithmError, Contains("no faces"));
  TriangleMesh bad = base;
  bad.faces[3][1] = static_cast<int>(bad.vertices.size());
  CHECK_THROWS_MATCHES_TEXT(MeshLocator(bad), AlgorithmError, Contains("face 3"));
  bad = base;
  bad.vertices[2].x() = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS(MeshLocator(bad), AlgorithmError);
}

TEST_CASE("displacement options: check() names the field", "[displacement][errors]") {
  DisplacementOptions o;
  CHECK_NOTHROW(o.check());
  o.filter = "gausian";
  CHECK_THROWS_MATCHES_TEXT(o.check(), ConfigError, Contains("filter") && Contains("gaussian"));
  o = DisplacementOptions();
  o.hole_fill = "zero";
  CHECK_THROWS_MATCHES_TEXT(o.check(), ConfigError, Contains("hole_fill") && Contains("thin_plate"));
  o = DisplacementOptions();
  o.sigma_factor = 0.0;
  CHECK_THROWS_MATCHES_TEXT(o.check(), ConfigError, Contains("sigma_factor"));
  o = DisplacementOptions();
  o.residual_passes = -1;
  CHECK_THROWS_MATCHES_TEXT(o.check(), ConfigError, Contains("residual_passes"));
  o = DisplacementOptions();
  o.fine_residual_passes = -1;
  CHECK_THROWS_MATCHES_TEXT(o.check(), ConfigError, Contains("fine_residual_passes"));
  o = DisplacementOptions();
  o.rim_offset = -0.1;
  CHECK_THROWS_MATCHES_TEXT(o.check(), ConfigError, Contains("rim_offset"));
}

TEST_CASE("displacement plugins: registered, every filter and hole treatment runs", "[displacement]") {
  register_displacers();
  register_displacers();  // idempotent
  CHECK(displacement_filters().names() == std::vector<std::string>{"adaptive", "gaussian"});
  CHECK(hole_treatments().names() == std::vector<std::string>{"harmonic", "membrane", "thin_plate"});
  const SphereSdf f(0.6);
  const TriangleMesh base = base_mesh(f, Vec3(0.6, 0, 0), 0.08);
  std::vector<Vec3> pts;
  for (const Vec3& v : fibonacci_directions(500)) pts.push_back(0.62 * v);
  for (const std::string& filter : displacement_filters().names())
    for (const std::string& fill : hole_treatments().names()) {
      DisplacementOptions o;
      o.filter = filter;
      o.hole_fill = fill;
      const DisplacementResult r = displace_mesh(f, base, pts, o);
      CHECK(r.summary["method"] == filter);
      CHECK(r.summary["vertices"].get<std::size_t>() == base.vertices.size());
      CHECK(r.summary["errors_after"]["e_avr"].get<double>() < 0.5 * r.summary["errors_before"]["e_avr"].get<double>());
    }
}

namespace {
class NanImplicit final : public Analytic {
 protected:
  double eval(const Vec3&, Vec3& g) const override {
    g = Vec3::UnitX();
    return std::numeric_limits<double>::quiet_NaN();
  }
};
}  // namespace

TEST_CASE("displacement: an implicit that yields NaN leaves no projectable point", "[displacement][errors]") {
  const SphereSdf sphere(0.6);
  const TriangleMesh base = base_mesh(sphere, Vec3(0.6, 0, 0), 0.08);
  const NanImplicit f;
  CHECK_THROWS_MATCHES_TEXT(displace_mesh(f, base, {Vec3(0.7, 0, 0)}), AlgorithmError,
                            Contains("no data point could be projected"));
}
