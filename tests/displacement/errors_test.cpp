// Bad input and bad options give clear errors naming the problem or the field.
#include <catch2/catch.hpp>
#include <limits>

#include "algorithms/displacement/displacement.hpp"
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
  o.sigma = -1;
  CHECK_THROWS_MATCHES_TEXT(o.check(), ConfigError, Contains("sigma"));
  o = DisplacementOptions();
  o.support = 0.0;
  CHECK_THROWS_MATCHES_TEXT(o.check(), ConfigError, Contains("support"));
  o = DisplacementOptions();
  o.min_points = 0;
  CHECK_THROWS_MATCHES_TEXT(o.check(), ConfigError, Contains("min_points"));
  o = DisplacementOptions();
  o.curvature_factor = -0.5;
  CHECK_THROWS_MATCHES_TEXT(o.check(), ConfigError, Contains("curvature_factor"));
  o = DisplacementOptions();
  o.rim_offset = -0.1;
  CHECK_THROWS_MATCHES_TEXT(o.check(), ConfigError, Contains("rim_offset"));
  o = DisplacementOptions();
  o.rim_min_feet = 0;
  CHECK_THROWS_MATCHES_TEXT(o.check(), ConfigError, Contains("rim_min_feet"));
  o = DisplacementOptions();
  o.rim_min_hole_vertices = 0;
  CHECK_THROWS_MATCHES_TEXT(o.check(), ConfigError, Contains("rim_min_hole_vertices"));
  o = DisplacementOptions();
  o.rim_rings = -1;
  CHECK_THROWS_MATCHES_TEXT(o.check(), ConfigError, Contains("rim_rings"));
  o = DisplacementOptions();
  o.projection.newton_max_iterations = 0;
  CHECK_THROWS_MATCHES_TEXT(o.check(), ConfigError, Contains("newton_max_iterations"));
  o = DisplacementOptions();
  o.projection.locator.snap_tolerance = 0.5;
  CHECK_THROWS_MATCHES_TEXT(o.check(), ConfigError, Contains("snap_tolerance"));
}

TEST_CASE("displacement plugin: registered, options listed, runs", "[displacement]") {
  register_displacers();
  register_displacers();  // idempotent
  REQUIRE(displacers().contains("gaussian"));
  auto d = displacers().create("gaussian", "test");
  struct Names final : FieldVisitor {
    std::vector<std::string> names;
    void field(const char* n, bool&, const char* doc) override { add(n, doc); }
    void field(const char* n, int&, const char* doc) override { add(n, doc); }
    void field(const char* n, double&, const char* doc) override { add(n, doc); }
    void field(const char* n, std::string&, const char* doc) override { add(n, doc); }
    void field(const char* n, std::vector<double>&, const char* doc) override { add(n, doc); }
    void add(const char* n, const char* doc) {
      names.push_back(n);
      CHECK(std::string(doc).size() > 10);
    }
  } names;
  d->options().visit(names);
  CHECK(std::find(names.names.begin(), names.names.end(), "sigma") != names.names.end());
  CHECK(std::find(names.names.begin(), names.names.end(), "snap_tolerance") != names.names.end());
  const SphereSdf f(0.6);
  const TriangleMesh base = base_mesh(f, Vec3(0.6, 0, 0), 0.08);
  std::vector<Vec3> pts;
  for (const Vec3& v : fibonacci_directions(500)) pts.push_back(0.62 * v);
  const DisplacementResult r = d->displace(f, base, pts);
  CHECK(r.summary["method"] == "gaussian");
  CHECK(r.summary["vertices"].get<std::size_t>() == base.vertices.size());
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
