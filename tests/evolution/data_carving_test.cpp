// The data's carving (data_carving.hpp): its ball follows the local spacing, so a density ramp keeps its
// solid where one ball size for the whole cloud slips into it; separate objects stay separate; the sign is
// negative inside and the data end up inside the initial level set made from it.
#include <catch2/catch.hpp>

#include <cmath>

#include "algorithms/evolution/data_carving.hpp"
#include "framework/core/error.hpp"
#include "tests/evolution/fixtures.hpp"

using namespace dtsl;
using namespace dtsl::test;

namespace {
Vec3 centroid(const std::vector<Vec3>& points, int side) {
  Vec3 sum = Vec3::Zero();
  int n = 0;
  for (const Vec3& p : points)
    if ((p.x() > 0) == (side > 0)) sum += p, ++n;
  return sum / n;
}
}  // namespace

TEST_CASE("the carving of a torus with a 40x density ramp keeps its tube solid and its hole open", "[carve]") {
  const std::vector<Vec3> points = dataset_points(
      "{name: torus40, shape: {type: torus, R: 1.0, r: 0.4}, "
      "sampler: {type: area, count: 4000, density_ratio: 40, density_axis: x}}");
  // The tube's centre circle: the radius halfway between the data's nearest and farthest from the z axis.
  double inner = 1e9, outer = 0.0;
  for (const Vec3& p : points) {
    const double r = std::hypot(p.x(), p.y());
    inner = std::min(inner, r), outer = std::max(outer, r);
  }
  const double centre = 0.5 * (inner + outer);
  const DataCarving carving(points, 2.0);
  for (int k = 0; k < 16; ++k) {
    const double t = 2.0 * M_PI * k / 16.0;
    INFO("angle " << t);
    CHECK(carving(Vec3(centre * std::cos(t), centre * std::sin(t), 0.0)) < 0.0);
  }
  CHECK(carving(Vec3::Zero()) > 0.0);
  CHECK(carving(Vec3(0.0, 0.0, 1.5)) > 0.0);
}

TEST_CASE("the carving keeps two separate spheres apart", "[carve]") {
  const std::vector<Vec3>& points = two_spheres_data();
  const DataCarving carving(points, 2.0);
  const Vec3 left = centroid(points, -1), right = centroid(points, 1);
  CHECK(carving(left) < 0.0);
  CHECK(carving(right) < 0.0);
  CHECK(carving(0.5 * (left + right)) > 0.0);
}

TEST_CASE("the initial level set from the carving holds every data point inside", "[carve]") {
  const std::vector<Vec3>& points = torus_data();
  EvolutionOptions o = test_options("distance_balloon", "eigen_cg", 5);
  auto basis = std::make_shared<TSplineBasis>(build_octree(points, o.tmesh));
  const DataCarving carving(points, 2.0);
  const TSpline f = initial_level_set(basis, points, [&carving](const Vec3& x) { return carving(x); });
  double finest = 1e9;
  for (int l = 0; l < f.tmesh().leaf_count(); ++l) finest = std::min(finest, f.tmesh().leaf_side(l));
  for (const Vec3& p : points) REQUIRE(f.evaluate(p) <= -0.25 * finest + 1e-12);
  CHECK(f.evaluate(Vec3::Zero()) > 0.0);
}

TEST_CASE("the carving rejects too few, coplanar or coincident points and a non-positive alpha", "[carve]") {
  const std::vector<Vec3> three{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  CHECK_THROWS_AS(DataCarving(three, 2.0), AlgorithmError);
  std::vector<Vec3> flat;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) flat.emplace_back(0.1 * i, 0.1 * j, 0.0);
  CHECK_THROWS_AS(DataCarving(flat, 2.0), AlgorithmError);
  CHECK_THROWS_AS(DataCarving(std::vector<Vec3>(10, Vec3(0.1, 0.2, 0.3)), 2.0), AlgorithmError);
  CHECK_THROWS_AS(DataCarving(sphere_data(200), 0.0), AlgorithmError);
}

TEST_CASE("the carving opens the gap between two spheres a few spacings apart", "[carve]") {
  // Gap 0.095 in the frame, about 3.5 spacings (pair.cpp): the ball of 2.5 spacings cannot pass it
  // everywhere, the second flood between the data's pieces does.
  const std::vector<Vec3> points =
      dataset_points("{name: pair, shape: {type: pair, object: sphere, gap: 0.1}, sampler: {type: area, count: 5000}}");
  const DataCarving carving(points, 2.5);
  CHECK(carving.summary().data_pieces == 2);
  CHECK(carving.summary().reopened_cells > 0);
  const Vec3 left = centroid(points, -1), right = centroid(points, 1);
  CHECK(carving(left) < 0.0);
  CHECK(carving(right) < 0.0);
  // Across the gap, on and off the axis between the centres: outside.
  int reopened = 0;
  for (const double y : {0.0, 0.1, -0.2})
    for (const double z : {0.0, 0.15}) {
      INFO("y " << y << " z " << z);
      CHECK(carving(Vec3(0.0, y, z)) > 0.0);
      reopened += carving.reopened(Vec3(0.0, y, z));
    }
  CHECK(reopened > 0);  // the second flood opened the gap's middle
  CHECK_FALSE(carving.reopened(left));
  CHECK(carving.evaluate(left).piece != carving.evaluate(right).piece);
}
