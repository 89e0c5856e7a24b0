// d(x) and grad d from the kd-tree against brute force.
#include <catch2/catch.hpp>

#include <random>

#include "algorithms/evolution/data_distance.hpp"
#include "framework/core/error.hpp"
#include "tests/tspline/point_sets.hpp"

using namespace dtsl;

TEST_CASE("data distance: nearest point, distance and direction equal brute force", "[evolution][distance]") {
  const std::vector<Vec3> data = test::nonuniform_torus_points(3000, 0.6, 0.25, 6.0, 5);
  const DataDistance tree(data);
  CHECK(tree.size() == data.size());
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1.3, 1.3);
  std::vector<Vec3> queries;
  for (int k = 0; k < 500; ++k) queries.emplace_back(u(rng), u(rng), u(rng));
  queries.push_back(data[17]);  // on a data point: d = 0, no direction
  const std::vector<NearestData> all = tree.nearest_all(queries);
  for (std::size_t q = 0; q < queries.size(); ++q) {
    double best = 1e300;
    for (const Vec3& p : data) best = std::min(best, (p - queries[q]).norm());
    const NearestData& n = all[q];
    CHECK(n.distance == Approx(best).margin(1e-14));
    CHECK((data[n.index] - queries[q]).norm() == Approx(best).margin(1e-14));
    if (n.distance > 0) {
      CHECK(n.direction.norm() == Approx(1.0));
      CHECK((queries[q] - n.distance * n.direction - data[n.index]).norm() < 1e-12);
    } else {
      CHECK(n.direction == Vec3::Zero());
    }
  }
}

TEST_CASE("data distance: no points or a non-finite point is an AlgorithmError", "[evolution][distance]") {
  CHECK_THROWS_AS(DataDistance(std::vector<Vec3>{}), AlgorithmError);
  CHECK_THROWS_AS(DataDistance({Vec3::Zero(), Vec3(NAN, 0, 0)}), AlgorithmError);
}
