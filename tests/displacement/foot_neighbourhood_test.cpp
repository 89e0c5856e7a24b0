// The feet around a vertex and their Gaussian taps: the contract every displacement filter builds on.
#include <catch2/catch.hpp>
#include <cmath>

#include "algorithms/displacement/foot_neighbourhood.hpp"
#include "tests/displacement/implicits.hpp"
#include "tests/displacement/support.hpp"

using namespace dtsl;
using namespace dtsl::test;

namespace {

struct Setup {
  SphereSdf f{0.6};
  TriangleMesh base = base_mesh(f, Vec3(0.6, 0, 0), 0.08);
  std::vector<Vec3> points, normals;
  ProjectionResult projection;
  explicit Setup(int n) {
    // Points of the sphere of radius 0.62, none within 0.3 of (0, 0, 0.62): a hole around the pole.
    for (const Vec3& d : fibonacci_directions(n))
      if ((0.62 * d - Vec3(0, 0, 0.62)).norm() > 0.3) points.push_back(0.62 * d);
    const MeshLocator locator(base);
    projection = project_data(f, locator, points);
    for (const Vec3& v : base.vertices) normals.push_back(v.normalized());
  }
};

}  // namespace

TEST_CASE("foot neighbourhoods: Gaussian taps sum to 1 within the support, none at a hole", "[displacement][feet]") {
  const Setup s(6000);
  const double width = 0.05;
  const FootNeighbourhoods feet(s.base, s.projection, s.normals, {width});
  CHECK_FALSE(feet.widened());
  CHECK(feet.stride() == 1);
  int holes = 0;
  for (long v = 0; v < static_cast<long>(s.base.vertices.size()); ++v) {
    FootReach reach;
    feet.gather(v, reach, 0);
    FilterTaps taps;
    const bool ok = feet.gaussian_taps(reach, width, taps);
    const Vec3& x = s.base.vertices[v];
    if ((x - Vec3(0, 0, 0.6)).norm() < 0.1) {  // deep in the hole: no foot within 3 widths
      CHECK_FALSE(ok);
      ++holes;
      continue;
    }
    if (!ok) continue;  // near the hole's rim
    double sum = 0.0;
    for (const auto& [k, w] : taps) {
      sum += w;
      CHECK(w > 0.0);
      CHECK((s.projection.foot_points[k] - x).norm() <= kFilterSupport * width + 1e-12);
    }
    CHECK(sum == Approx(1.0).epsilon(1e-12));
    // Far from the hole the feet lie all round: their centroid is near the vertex.
    if ((x - Vec3(0, 0, 0.6)).norm() > 0.6) CHECK(feet.one_sidedness(v, taps, width) < 0.3);
  }
  CHECK(holes > 0);
}

TEST_CASE("foot neighbourhoods: dense data thin the feet of the widest widths", "[displacement][feet]") {
  const Setup s(60000);  // far more than 8 feet per base vertex
  REQUIRE(s.points.size() > 8 * 3 * s.base.vertices.size());
  const FootNeighbourhoods ladder(s.base, s.projection, s.normals, {0.02, 0.028, 0.04, 0.057, 0.08});
  CHECK(ladder.widened());
  CHECK(ladder.near() == 2);
  CHECK(ladder.stride() >= 3);
  // The widest width's reach from the thinned feet holds about 1/stride of them, grouped by width.
  const long v = 0;
  FootReach all, thinned;
  ladder.gather(v, all, ladder.near());
  ladder.gather(v, thinned, 4);
  FilterTaps taps;
  CHECK(ladder.gaussian_taps(thinned, 0.08, taps));
  const FootNeighbourhoods widest(s.base, s.projection, s.normals, {0.08});  // one width: every foot
  FootReach every;
  widest.gather(v, every, 0);
  CHECK(thinned.size() > 0);
  CHECK(thinned.size() * 2 < every.size());
  CHECK(all.size() < every.size());
  for (std::size_t t = 1; t < thinned.size(); ++t) {
    // a width's feet are a prefix: the squared distances' width groups do not decrease
    const auto group = [](double d2) {
      int j = 0;
      for (double w : {0.02, 0.028, 0.04, 0.057}) j += d2 > std::pow(kFilterSupport * w, 2) ? 1 : 0;
      return j;
    };
    CHECK(group(thinned[t].second) >= group(thinned[t - 1].second));
  }
}
