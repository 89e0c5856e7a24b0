#include "algorithms/evolution/data_distance.hpp"

#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "framework/core/error.hpp"

namespace dtsl {

namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using BaseTraits = CGAL::Search_traits_3<Kernel>;
// The tree stores indices into `points`; the adapter reads coordinates through the property map, so
// a query returns which data point is nearest, not just where it is.
using PointMap = CGAL::Pointer_property_map<Point>::type;
using Traits = CGAL::Search_traits_adapter<std::size_t, PointMap, BaseTraits>;
using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;
using Tree = Search::Tree;
using Distance = Search::Distance;
}  // namespace

struct DataDistance::Impl {
  std::vector<Point> points;
  std::unique_ptr<Tree> tree;
};

DataDistance::DataDistance(const std::vector<Vec3>& points) : impl_(std::make_unique<Impl>()) {
  if (points.empty()) throw AlgorithmError("data distance: no data points");
  impl_->points.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite())
      throw AlgorithmError("data distance: data point " + std::to_string(i) + " is not finite");
    impl_->points.emplace_back(points[i].x(), points[i].y(), points[i].z());
  }
  std::vector<std::size_t> ids(points.size());
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = i;
  impl_->tree = std::make_unique<Tree>(ids.begin(), ids.end(), Tree::Splitter(),
                                       Traits(CGAL::make_property_map(impl_->points)));
  impl_->tree->build();  // now, so that concurrent queries never trigger the lazy build
}

DataDistance::~DataDistance() = default;

std::size_t DataDistance::size() const { return impl_->points.size(); }

NearestData DataDistance::nearest(const Vec3& x) const {
  const Point q(x.x(), x.y(), x.z());
  Search search(*impl_->tree, q, 1, 0.0, true,
                Distance(CGAL::make_property_map(impl_->points)));
  NearestData r;
  const auto it = search.begin();
  r.index = int(it->first);
  const Vec3 p(impl_->points[it->first].x(), impl_->points[it->first].y(), impl_->points[it->first].z());
  const Vec3 diff = x - p;
  r.distance = diff.norm();
  if (r.distance > 0.0) r.direction = diff / r.distance;
  return r;
}

std::vector<double> DataDistance::local_spacing(int k) const {
  if (k < 1) throw AlgorithmError("local spacing: k must be at least 1, got " + std::to_string(k));
  return mean_neighbour_distance(nearest_neighbours(k));
}

NearestNeighbours DataDistance::nearest_neighbours(int k) const {
  if (k < 1) throw AlgorithmError("nearest neighbours: k must be at least 1, got " + std::to_string(k));
  const long n = long(impl_->points.size());
  NearestNeighbours out;
  out.k = k;
  out.index.assign(std::size_t(n) * std::size_t(k), -1);
  out.distance.assign(std::size_t(n) * std::size_t(k), 0.0);
#pragma omp parallel for schedule(dynamic, 256)
  for (long i = 0; i < n; ++i) {
    // k + 1 neighbours: the point itself comes first at distance 0.
    Search search(*impl_->tree, impl_->points[i], unsigned(std::min<long>(k + 1, n)), 0.0, true,
                  Distance(CGAL::make_property_map(impl_->points)));
    int count = 0;
    for (const auto& hit : search) {
      if (hit.first == std::size_t(i)) continue;
      if (count == k) break;
      const std::size_t slot = std::size_t(i) * std::size_t(k) + std::size_t(count++);
      out.index[slot] = int(hit.first);
      out.distance[slot] = std::sqrt(hit.second);
    }
  }
  return out;
}

std::vector<double> mean_neighbour_distance(const NearestNeighbours& neighbours) {
  const std::size_t k = std::size_t(neighbours.k), n = k > 0 ? neighbours.index.size() / k : 0;
  std::vector<double> mean(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    double sum = 0.0;
    int count = 0;
    for (std::size_t m = 0; m < k; ++m)
      if (neighbours.index[i * k + m] >= 0) {
        sum += neighbours.distance[i * k + m];
        ++count;
      }
    mean[i] = count > 0 ? sum / count : 0.0;
  }
  return mean;
}

std::vector<NearestData> DataDistance::nearest_all(const std::vector<Vec3>& queries) const {
  std::vector<NearestData> out(queries.size());
  const long n = long(queries.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (long i = 0; i < n; ++i) out[i] = nearest(queries[i]);
  return out;
}

}  // namespace dtsl
