// Oriented normals: CGAL jet fitting (or PCA) for the directions, CGAL's minimum-spanning-tree
// propagation for one consistent orientation, and the rule that picks the source a run reports.
#ifndef CGAL_EIGEN3_ENABLED
#define CGAL_EIGEN3_ENABLED  // jet fitting needs an SVD; Eigen is already a dependency of the core
#endif
#include "algorithms/normals/normals.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/compute_average_spacing.h>
#include <CGAL/jet_estimate_normals.h>
#include <CGAL/mst_orient_normals.h>
#include <CGAL/pca_estimate_normals.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <boost/iterator/counting_iterator.hpp>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <limits>
#include <numeric>
#include <string>
#include <tuple>

#include "framework/core/error.hpp"

namespace dtsl {

void NormalSourceOptions::visit(FieldVisitor& v) {
  v.field("normals", normals,
          "where normals come from: ground_truth | jet_mst | pca_mst | auto (ground truth if the data has it, "
          "else jet_mst)");
  v.field("normal_neighbours", normal_neighbours, "k of the k-nearest-neighbour fits and of the orientation graph");
}

void NormalSourceOptions::check() const {
  check_one_of("normals", normals, {"auto", "ground_truth", "jet_mst", "pca_mst"});
  check_range("normal_neighbours", normal_neighbours, 3, 200);
}

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
// The original index travels with each point: mst_orient_normals reorders the range.
using Item = std::tuple<K::Point_3, K::Vector_3, std::size_t>;
using PointMap = CGAL::Nth_of_tuple_property_map<0, Item>;
using NormalMap = CGAL::Nth_of_tuple_property_map<1, Item>;
using PointPmap = CGAL::Pointer_property_map<K::Point_3>::type;
// Marks the one seed of an orientation pass.
struct IsSeed {
  using key_type = Item;
  using value_type = bool;
  using reference = bool;
  using category = boost::readable_property_map_tag;
  std::size_t seed;
  friend bool get(const IsSeed& m, const Item& it) { return std::get<2>(it) == m.seed; }
};

// Orients [first, end) -- points the graph search did not reach -- from one seed, and moves the ones
// it reached to the front of that range; returns their number. Let r be the unoriented point nearest
// to an oriented point o. If r is a few sample spacings away and lies roughly in o's tangent plane, it
// continues o's surface (the k-neighbour graph merely fell apart) and takes o's orientation. Otherwise
// the rest is another object and is seeded like the first pass, at its highest point with +z: aligning
// with o would be wrong there, as facing sides of two objects have opposite normals.
template <class NamedParameters>
std::size_t orient_rest(std::vector<Item>& items, std::vector<Item>::iterator first, unsigned int k,
                        double spacing, const NamedParameters& np) {
  using TreeTraits = CGAL::Search_traits_adapter<std::size_t, PointPmap, CGAL::Search_traits_3<K>>;
  using Search = CGAL::Orthogonal_k_neighbor_search<TreeTraits>;
  const std::size_t oriented = static_cast<std::size_t>(first - items.begin());
  std::vector<K::Point_3> positions;
  positions.reserve(oriented);
  for (auto it = items.begin(); it != first; ++it) positions.push_back(std::get<0>(*it));
  const PointPmap pmap = CGAL::make_property_map(positions);
  const typename Search::Tree tree(boost::counting_iterator<std::size_t>(0),
                                   boost::counting_iterator<std::size_t>(oriented),
                                   typename Search::Tree::Splitter(), TreeTraits(pmap));
  double best = std::numeric_limits<double>::infinity();
  std::size_t nearest = 0;
  auto seed = first;
  for (auto it = first; it != items.end(); ++it) {
    const Search search(tree, std::get<0>(*it), 1, 0, true, typename Search::Distance(pmap));
    const auto hit = search.begin();
    if (hit->second < best) best = hit->second, nearest = hit->first, seed = it;
  }
  const K::Vector_3& toward = std::get<1>(items[nearest]);
  const K::Vector_3 gap = std::get<0>(*seed) - std::get<0>(items[nearest]);
  const bool same_surface = std::sqrt(best) <= 5.0 * spacing && std::abs(gap * toward) <= 0.5 * std::sqrt(best);
  if (same_surface) {
    K::Vector_3& normal = std::get<1>(*seed);
    if (normal * toward < 0) normal = -normal;
  } else {
    seed = std::max_element(first, items.end(), [](const Item& a, const Item& b) {
      return std::get<0>(a).z() < std::get<0>(b).z();
    });
    if (std::get<1>(*seed).z() < 0) std::get<1>(*seed) = -std::get<1>(*seed);
  }
  std::vector<Item> rest(first, items.end());
  const std::size_t seed_index = std::get<2>(*seed);
  std::size_t done = 1;
  if (rest.size() >= 3) {
    const unsigned int k_rest = std::min<unsigned int>(k, static_cast<unsigned int>(rest.size() - 1));
    done = static_cast<std::size_t>(
        CGAL::mst_orient_normals(rest, k_rest, np.point_is_constrained_map(IsSeed{seed_index})) - rest.begin());
  } else {  // too few for a graph: the seed alone is oriented
    std::stable_partition(rest.begin(), rest.end(), [&](const Item& it) { return std::get<2>(it) == seed_index; });
  }
  std::copy(rest.begin(), rest.end(), first);
  return done;
}

}  // namespace

std::vector<Vec3> estimate_oriented_normals(const std::vector<Vec3>& points, int k, bool use_jet,
                                            std::size_t* unoriented) {
  const std::string what = use_jet ? "jet_mst normals" : "pca_mst normals";
  if (k < 3) throw AlgorithmError(what + ": k must be at least 3, got " + std::to_string(k));
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite())
      throw AlgorithmError(what + ": point " + std::to_string(i) + " has a NaN or infinite coordinate");

  // Exact duplicates (mesh vertices repeated along seams, say) can make a neighbourhood of coincident
  // points, on which CGAL's jet fit divides by zero and crashes: estimate on the distinct points and
  // copy each normal to the duplicates.
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto less = [&](std::size_t a, std::size_t b) {
    const Vec3 &p = points[a], &q = points[b];
    return std::tie(p.x(), p.y(), p.z()) < std::tie(q.x(), q.y(), q.z());
  };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return less(a, b) || (!less(b, a) && a < b); });
  std::vector<std::size_t> distinct_of(points.size());
  std::vector<Item> items;
  for (std::size_t j = 0; j < order.size(); ++j) {
    const std::size_t i = order[j];
    if (j == 0 || less(order[j - 1], i)) {
      const Vec3& p = points[i];
      items.emplace_back(K::Point_3(p.x(), p.y(), p.z()), K::Vector_3(0, 0, 0), items.size());
    }
    distinct_of[i] = items.size() - 1;
  }
  if (items.size() < 3 || items.size() < static_cast<std::size_t>(k) + 1)
    throw AlgorithmError(what + ": " + std::to_string(items.size()) + " distinct points (of " +
                         std::to_string(points.size()) + ") are too few for k = " + std::to_string(k) +
                         " neighbours (need at least " + std::to_string(std::max(3, k + 1)) + ")");

  const auto np = CGAL::parameters::point_map(PointMap()).normal_map(NormalMap());
  const unsigned int kk = static_cast<unsigned int>(k);
  if (use_jet) {
    // A quadric jet needs 6 points; below that fit a plane (degree 1), which needs 3.
    CGAL::jet_estimate_normals<CGAL::Sequential_tag>(items, kk, np.degree_fitting(k >= 6 ? 2 : 1));
  } else {
    CGAL::pca_estimate_normals<CGAL::Sequential_tag>(items, kk, np);
  }
  for (const Item& it : items) {
    const K::Vector_3& n = std::get<1>(it);
    const Vec3 v(n.x(), n.y(), n.z());
    if (!v.allFinite() || v.squaredNorm() == 0.0)
      throw AlgorithmError(what + ": no normal could be fitted at (" + std::to_string(std::get<0>(it).x()) + ", " +
                           std::to_string(std::get<0>(it).y()) + ", " + std::to_string(std::get<0>(it).z()) +
                           "): its " + std::to_string(k) + " neighbours are degenerate");
  }
  // CGAL seeds at the highest point with +z (outward for a closed surface) and propagates along the
  // minimum spanning tree of the k-neighbour graph weighted by 1 - |n_i . n_j|. Points of other graph
  // components come back unoriented; see orient_rest.
  auto first = CGAL::mst_orient_normals(items, kk, np);
  const double spacing =
      first == items.end() ? 0.0 : CGAL::compute_average_spacing<CGAL::Sequential_tag>(items, kk, np);
  while (first != items.end()) {
    const std::size_t done = orient_rest(items, first, kk, spacing, np);
    if (done == 0) break;  // cannot happen (the seed is always oriented), but never loop
    first += static_cast<long>(done);
  }
  if (unoriented) *unoriented = static_cast<std::size_t>(std::distance(first, items.end()));

  std::vector<Vec3> distinct_normals(items.size());
  for (const Item& it : items) {
    const K::Vector_3& n = std::get<1>(it);
    distinct_normals[std::get<2>(it)] = Vec3(n.x(), n.y(), n.z()).normalized();
  }
  std::vector<Vec3> normals(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) normals[i] = distinct_normals[distinct_of[i]];
  return normals;
}

PointCloud with_normals(const PointCloud& cloud, const NormalSourceOptions& options, std::string& source_used) {
  options.check();
  const bool use_truth = options.normals == "ground_truth" || (options.normals == "auto" && cloud.has_normals());
  if (use_truth) {
    if (!cloud.has_normals())
      throw AlgorithmError("normals: source 'ground_truth' requested but the point cloud has no normals "
                           "(use normals: auto, jet_mst or pca_mst)");
    for (std::size_t i = 0; i < cloud.normals.size(); ++i)
      if (!cloud.normals[i].allFinite() || cloud.normals[i].squaredNorm() == 0.0)
        throw AlgorithmError("normals: ground-truth normal " + std::to_string(i) + " is zero or not finite");
    source_used = "ground_truth";
    return cloud;
  }
  const bool jet = options.normals != "pca_mst";  // auto without ground truth falls back to jet_mst
  PointCloud out;
  out.points = cloud.points;
  out.normals = estimate_oriented_normals(cloud.points, options.normal_neighbours, jet);
  source_used = jet ? "jet_mst" : "pca_mst";
  return out;
}

}  // namespace dtsl
