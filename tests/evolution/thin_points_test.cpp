// thin_points: the level-set stage's data at large inputs (thin_points.hpp, EvolutionOptions::max_points).
#include <catch2/catch.hpp>

#include "algorithms/evolution/evolution.hpp"
#include "algorithms/evolution/thin_points.hpp"
#include "framework/core/error.hpp"

using namespace dtsl;

namespace {

std::vector<Vec3> numbered(int n) {
  std::vector<Vec3> p;
  for (int k = 0; k < n; ++k) p.emplace_back(double(k), 0.0, 0.0);
  return p;
}

}  // namespace

TEST_CASE("thin_points: exactly max_points, evenly spread over the input order, deterministic", "[evolution][thin]") {
  for (const auto& [n, m] : std::vector<std::pair<int, int>>{{1000, 300}, {1001, 1000}, {12345, 100}, {50, 49}}) {
    const std::vector<Vec3> all = numbered(n);
    const std::vector<Vec3> kept = thin_points(all, std::size_t(m));
    REQUIRE(int(kept.size()) == m);
    CHECK(kept == thin_points(all, std::size_t(m)));
    // Every kept point is an input point, in input order, and the gaps are the stride n/m (rounded).
    const double stride = double(n) / m;
    for (int i = 0; i < m; ++i) {
      const double k = kept[i].x();
      CHECK(k >= 0.0);
      CHECK(k < n);
      CHECK(std::abs(k - (i + 1) * stride) <= stride);  // covers the whole input, first to last
      if (i > 0) {
        CHECK(k > kept[i - 1].x());
        CHECK(k - kept[i - 1].x() <= std::ceil(stride));
      }
    }
  }
}

TEST_CASE("thin_points: all points when max_points is 0 or not smaller", "[evolution][thin]") {
  const std::vector<Vec3> all = numbered(500);
  CHECK(thin_points(all, 0) == all);
  CHECK(thin_points(all, 500) == all);
  CHECK(thin_points(all, 10000) == all);
  CHECK(thin_points({}, 10).empty());
}

TEST_CASE("evolution max_points: out-of-range values are named", "[evolution][thin][bad]") {
  EvolutionOptions o;
  o.max_points = 50;
  CHECK_THROWS_WITH(o.check(), Catch::Contains("max_points"));
  o.max_points = -1;
  CHECK_THROWS_WITH(o.check(), Catch::Contains("max_points"));
  o.max_points = 0;
  CHECK_NOTHROW(o.check());
}
