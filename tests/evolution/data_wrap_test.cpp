// The data's wrap (data_wrap.hpp): its topology is the data's where holes and gaps are wider than a few
// spacings, its distance is signed (negative inside, the data inside), and the initial level set made from it
// keeps every data point inside.
#include <catch2/catch.hpp>

#include "algorithms/evolution/data_wrap.hpp"
#include "framework/core/error.hpp"
#include "tests/evolution/fixtures.hpp"

using namespace dtsl;
using namespace dtsl::test;

TEST_CASE("the wrap of a torus has genus 1 and of two separate spheres two components", "[wrap]") {
  const DataWrap torus(torus_data(), 3.0, kWrapOffsetSpacings);
  CHECK(torus.summary().components == 1);
  CHECK(torus.summary().genus == 1);
  const DataWrap two(two_spheres_data(), 3.0, kWrapOffsetSpacings);
  CHECK(two.summary().components == 2);
  CHECK(two.summary().genus == 0);
}

TEST_CASE("the wrap of a plate keeps its through-holes open", "[wrap]") {
  const std::vector<Vec3> plate = dataset_points(
      "{name: plate2, shape: {type: plate_holes, hole_diameters: [0.3, 0.2]}, sampler: {type: area, count: 5000}}");
  const DataWrap wrap(plate, 3.0, kWrapOffsetSpacings);
  CHECK(wrap.summary().components == 1);
  CHECK(wrap.summary().genus == 2);
}

TEST_CASE("the wrap's distance is negative inside, positive outside, and the data are inside", "[wrap]") {
  const std::vector<Vec3> points = sphere_data(2000);  // radius 0.8 about the origin
  const DataWrap wrap(points, 3.0, kWrapOffsetSpacings);
  const WrapSummary& s = wrap.summary();
  CHECK(s.spacing > 0.0);
  CHECK(s.alpha == Approx(3.0 * s.spacing));
  CHECK(wrap(Vec3::Zero()) < -0.7);
  CHECK(wrap(Vec3(2.0, 0.0, 0.0)) > 1.1);
  for (const Vec3& p : points) {
    REQUIRE(wrap(p) < 0.0);
    REQUIRE(wrap(p) > -2.0 * s.offset);
  }
}

TEST_CASE("the initial level set from the wrap holds every data point a quarter leaf inside", "[wrap]") {
  const std::vector<Vec3>& points = torus_data();
  EvolutionOptions o = test_options("distance_balloon", "eigen_cg", 5);
  auto basis = std::make_shared<TSplineBasis>(build_octree(points, o.tmesh));
  const DataWrap wrap(points, 3.0, kWrapOffsetSpacings);
  const TSpline f = initial_level_set(basis, points, [&wrap](const Vec3& x) { return wrap(x); });
  double finest = 1e9;
  for (int l = 0; l < f.tmesh().leaf_count(); ++l) finest = std::min(finest, f.tmesh().leaf_side(l));
  for (const Vec3& p : points) REQUIRE(f.evaluate(p) <= -0.25 * finest + 1e-12);
  CHECK(f.evaluate(Vec3(0.0, 0.0, 0.0)) > 0.0);  // the torus's hole is outside
}

TEST_CASE("the wrap rejects too few points, coincident points and non-positive factors", "[wrap]") {
  const std::vector<Vec3> three{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  CHECK_THROWS_AS(DataWrap(three, 3.0, 0.5), AlgorithmError);
  const std::vector<Vec3> same(10, Vec3(0.1, 0.2, 0.3));
  CHECK_THROWS_AS(DataWrap(same, 3.0, 0.5), AlgorithmError);
  CHECK_THROWS_AS(DataWrap(sphere_data(200), 0.0, 0.5), AlgorithmError);
  CHECK_THROWS_AS(DataWrap(sphere_data(200), 3.0, -1.0), AlgorithmError);
  EvolutionOptions o;
  o.initial = "blob";
  CHECK_THROWS_AS(o.check(), ConfigError);
  o.initial = "wrap";
  o.wrap_alpha = 0.1;
  CHECK_THROWS_AS(o.check(), ConfigError);
}
