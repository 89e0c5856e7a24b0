// d(x): the distance from x to the nearest data point, and grad d, its unit direction away from that
// point — what every data-driven velocity of the level-set evolution reads (docs/design.md §1,
// "d(x) = distance to the nearest data point from a kd-tree, grad d its unit direction away from that
// point"). A CGAL kd-tree behind a pimpl, so CGAL stays out of the headers.
#pragma once

#include <memory>
#include <vector>

#include "framework/core/types.hpp"

namespace dtsl {

struct NearestData {
  double distance = 0.0;          ///< d(x) = |x - p|
  Vec3 direction = Vec3::Zero();  ///< grad d = (x - p) / |x - p|; zero where x coincides with p
  int index = -1;                 ///< p = points[index]
};

/// The k nearest other data points of every point, row-major (point i's are [i k, i k + k)), nearest
/// first; index -1 (distance 0) where there are fewer than k other points.
struct NearestNeighbours {
  int k = 0;
  std::vector<int> index;
  std::vector<double> distance;
};

/// The mean distance of every point to its neighbours (those with index >= 0; 0 for none): the local
/// spacing of DataDistance::local_spacing.
std::vector<double> mean_neighbour_distance(const NearestNeighbours& neighbours);

class DataDistance {
 public:
  /// Builds the tree now, so queries are const and thread-safe. AlgorithmError for no points or a
  /// non-finite coordinate.
  explicit DataDistance(const std::vector<Vec3>& points);
  ~DataDistance();
  DataDistance(const DataDistance&) = delete;
  DataDistance& operator=(const DataDistance&) = delete;

  /// The nearest data point (exact, ties broken by the tree). Thread-safe.
  NearestData nearest(const Vec3& x) const;
  /// nearest() of every query, in order (OpenMP-parallel).
  std::vector<NearestData> nearest_all(const std::vector<Vec3>& queries) const;

  std::size_t size() const;

  /// The local sampling spacing at every data point: the mean distance to its `k` nearest other data
  /// points (k >= 1; fewer when there are fewer points). Scale-free lengths of the evolution are
  /// multiples of it. OpenMP-parallel; throws AlgorithmError for k < 1.
  std::vector<double> local_spacing(int k) const;
  /// The k nearest other data points of every point. OpenMP-parallel; AlgorithmError for k < 1.
  NearestNeighbours nearest_neighbours(int k) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dtsl
