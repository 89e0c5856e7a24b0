// MeshDistance: exact point-to-mesh distance through a CGAL AABB tree over the mesh's triangles.
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

#include "framework/core/error.hpp"
#include "framework/metrics/metrics.hpp"

namespace dtsl {

namespace {
using K = CGAL::Simple_cartesian<double>;
using Triangles = std::vector<K::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

K::Point_3 to_cgal(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

// Interleaves the low 21 bits of x with two zero bits between each (one axis of a Morton code).
std::uint64_t spread_bits(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

// The points' indices in Morton (Z-curve) order of their positions within their bounding box.
std::vector<std::size_t> morton_order(const std::vector<Vec3>& points) {
  const BoundingBox box = bounding_box(points);
  const Vec3 extent = box.extent().cwiseMax(Vec3::Constant(1e-300));
  std::vector<std::pair<std::uint64_t, std::size_t>> keyed(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3 u = (points[i] - box.min).cwiseQuotient(extent) * 2097151.0;  // 2^21 - 1 cells per axis
    keyed[i] = {spread_bits(static_cast<std::uint64_t>(u.x())) | spread_bits(static_cast<std::uint64_t>(u.y())) << 1 |
                    spread_bits(static_cast<std::uint64_t>(u.z())) << 2,
                i};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < keyed.size(); ++i) order[i] = keyed[i].second;
  return order;
}

}  // namespace

struct MeshDistance::Impl {
  Triangles triangles;
  std::vector<int> face_of;  // tree triangle -> mesh face (degenerate faces are left out)
  Tree tree;
};

MeshDistance::MeshDistance(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
  if (mesh.faces.empty()) throw AlgorithmError("mesh: has no faces");
  const int n = static_cast<int>(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    if (!mesh.vertices[v].allFinite())
      throw AlgorithmError("mesh: vertex " + std::to_string(v) + " is not finite");
  impl_->triangles.reserve(mesh.faces.size());
  impl_->face_of.reserve(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& t = mesh.faces[f];
    for (int i : t)
      if (i < 0 || i >= n)
        throw AlgorithmError("mesh: face " + std::to_string(f) + " has vertex index " +
                             std::to_string(i) + " outside [0, " + std::to_string(n) + ")");
    // A zero-area face has no normal and its points lie on its neighbours' edges, so leaving it out
    // changes no distance on a sane mesh and keeps the closest face's normal meaningful.
    const Vec3& a = mesh.vertices[t[0]];
    if ((mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).squaredNorm() == 0.0) continue;
    impl_->triangles.emplace_back(to_cgal(a), to_cgal(mesh.vertices[t[1]]), to_cgal(mesh.vertices[t[2]]));
    impl_->face_of.push_back(static_cast<int>(f));
  }
  if (impl_->triangles.empty())
    throw AlgorithmError("mesh: all " + std::to_string(mesh.faces.size()) +
                         " faces have zero area");
  // Build everything now: CGAL otherwise builds lazily on the first query, which would make
  // concurrent const queries race.
  impl_->tree.insert(impl_->triangles.begin(), impl_->triangles.end());
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();
}

MeshDistance::~MeshDistance() = default;

MeshDistance::Hit MeshDistance::closest(const Vec3& p) const {
  if (!p.allFinite()) throw AlgorithmError("distance query: the point is not finite");
  const auto [q, it] = impl_->tree.closest_point_and_primitive(to_cgal(p));
  const Vec3 point(q.x(), q.y(), q.z());
  const int face = impl_->face_of[static_cast<std::size_t>(it - impl_->triangles.begin())];
  return {(point - p).norm(), point, face};
}

std::vector<MeshDistance::Hit> MeshDistance::closest_all(const std::vector<Vec3>& points) const {
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite()) throw AlgorithmError("distance query: point " + std::to_string(i) + " is not finite");
  // Random query order misses the cache on every tree level; along a space-filling curve consecutive
  // queries share most of their path: measured 3-4x faster on 100k samples of an 82k-face sphere.
  const std::vector<std::size_t> order = morton_order(points);
  std::vector<Hit> hits(points.size());
  const long n = static_cast<long>(points.size());
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 256)
#endif
  for (long j = 0; j < n; ++j) hits[order[j]] = closest(points[order[j]]);
  return hits;
}

}  // namespace dtsl
