// The data's pieces (data_pieces.hpp): the k-nearest-neighbour graph joins one sampled surface however
// non-uniform its sampling, and leaves two surfaces a few spacings apart in different pieces.
#include <catch2/catch.hpp>

#include <algorithm>
#include <set>

#include "algorithms/evolution/data_distance.hpp"
#include "algorithms/evolution/data_pieces.hpp"
#include "algorithms/evolution/support.hpp"
#include "framework/core/error.hpp"
#include "tests/evolution/fixtures.hpp"

using namespace dtsl;
using namespace dtsl::test;

TEST_CASE("the k nearest neighbours of every point equal brute force, nearest first", "[pieces]") {
  const std::vector<Vec3>& points = torus_data();
  const DataDistance data(points);
  const int k = 5;
  const std::vector<int> neighbours = data.nearest_neighbours(k).index;
  REQUIRE(neighbours.size() == points.size() * k);
  for (std::size_t i = 0; i < points.size(); i += 37) {
    std::vector<double> all;
    for (std::size_t j = 0; j < points.size(); ++j)
      if (j != i) all.push_back((points[j] - points[i]).norm());
    std::sort(all.begin(), all.end());
    for (int m = 0; m < k; ++m) {
      const int j = neighbours[i * k + m];
      REQUIRE(j >= 0);
      CHECK(std::size_t(j) != i);
      CHECK((points[j] - points[i]).norm() == Approx(all[m]).margin(1e-14));
    }
  }
  const std::vector<Vec3> three{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  const std::vector<int> padded = DataDistance(three).nearest_neighbours(4).index;
  CHECK(std::count(padded.begin(), padded.end(), -1) == 3 * 2);
  CHECK_THROWS_AS(data.nearest_neighbours(0), AlgorithmError);
}

TEST_CASE("two spheres a few spacings apart are two pieces, one per sphere", "[pieces]") {
  const std::vector<Vec3> points =
      dataset_points("{name: pair, shape: {type: pair, object: sphere, gap: 0.1}, sampler: {type: area, count: 5000}}");
  const std::vector<int> piece = data_pieces(DataDistance(points).nearest_neighbours(kSpacingNeighbours));
  REQUIRE(piece.size() == points.size());
  CHECK(std::set<int>(piece.begin(), piece.end()) == std::set<int>{0, 1});
  // The spheres lie on either side of x = 0: a point's piece is the first point's exactly when its side is.
  int mislabelled = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    mislabelled += (piece[i] == piece[0]) != ((points[i].x() > 0) == (points[0].x() > 0));
  CHECK(mislabelled == 0);
  const std::vector<std::vector<Vec3>> split = points_by_piece(points, piece);
  REQUIRE(split.size() == 2);
  CHECK(split[0].size() + split[1].size() == points.size());
}

TEST_CASE("a torus with a 40x density ramp is one piece", "[pieces]") {
  const std::vector<Vec3> points = dataset_points(
      "{name: torus40, shape: {type: torus, R: 1.0, r: 0.4}, "
      "sampler: {type: area, count: 4000, density_ratio: 40, density_axis: x}}");
  const std::vector<int> piece = data_pieces(DataDistance(points).nearest_neighbours(kSpacingNeighbours));
  CHECK(*std::max_element(piece.begin(), piece.end()) == 0);
}

TEST_CASE("points by piece rejects labels that do not match the points", "[pieces]") {
  const std::vector<Vec3> points{Vec3(0, 0, 0), Vec3(1, 0, 0)};
  CHECK_THROWS_AS(points_by_piece(points, {0}), AlgorithmError);
  CHECK_THROWS_AS(points_by_piece(points, {0, -1}), AlgorithmError);
  CHECK_THROWS_AS(data_pieces(DataDistance(points).nearest_neighbours(0)), AlgorithmError);
}
