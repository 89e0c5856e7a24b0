#include "algorithms/tspline/knots.hpp"

#include <algorithm>
#include <cstdint>

#include "framework/core/error.hpp"

namespace dtsl {

std::vector<Int3> control_vertices(const Octree& octree) {
  const std::uint64_t n = std::uint64_t(octree.resolution()) + 1;
  std::vector<std::uint64_t> keys;
  keys.reserve(std::size_t(octree.leaf_count()) * 8);
  for (int leaf = 0; leaf < octree.leaf_count(); ++leaf) {
    const Octree::Cell& c = octree.leaf(leaf);
    const int s = octree.cell_size(c.level);
    for (int o = 0; o < 8; ++o) {
      const std::uint64_t x = c.origin[0] + ((o & 1) ? s : 0), y = c.origin[1] + ((o & 2) ? s : 0),
                          z = c.origin[2] + ((o & 4) ? s : 0);
      keys.push_back((z * n + y) * n + x);
    }
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<Int3> vertices;
  vertices.reserve(keys.size());
  for (std::uint64_t k : keys) vertices.push_back({int(k % n), int(k / n % n), int(k / n / n)});
  return vertices;
}

namespace {

/// The next two cell-face coordinates met by the ray from `v` along `axis` in direction `dir` (+1/-1)
/// while it stays inside the domain; fewer when it leaves the domain first.
std::vector<int> faces_along_ray(const Octree& octree, const Int3& v, int axis, int dir) {
  const int R = octree.resolution();
  const int e = (axis + 1) % 3, f = (axis + 2) % 3;
  std::vector<int> faces;
  int pos = v[axis];
  while (faces.size() < 2 && (dir > 0 ? pos < R : pos > 0)) {
    int next = dir > 0 ? R : 0;
    // The cells adjacent to the ray just beyond `pos`: the finest cells on either side of the ray in
    // the two other axes (those inside the domain).
    for (int de = -1; de <= 0; ++de) {
      for (int df = -1; df <= 0; ++df) {
        Int3 probe;
        probe[axis] = dir > 0 ? pos : pos - 1;
        probe[e] = v[e] + de;
        probe[f] = v[f] + df;
        if (probe[e] < 0 || probe[e] >= R || probe[f] < 0 || probe[f] >= R) continue;
        const Octree::Cell& c = octree.leaf(octree.leaf_at(probe));
        const int face = dir > 0 ? c.origin[axis] + octree.cell_size(c.level) : c.origin[axis];
        next = dir > 0 ? std::min(next, face) : std::max(next, face);
      }
    }
    faces.push_back(next);
    pos = next;
  }
  return faces;
}

}  // namespace

LocalKnots local_knots(const Octree& octree, const Int3& vertex) {
  const int R = octree.resolution();
  for (int a = 0; a < 3; ++a)
    if (vertex[a] < 0 || vertex[a] > R) throw AlgorithmError("local_knots: vertex outside the lattice");
  LocalKnots knots;
  for (int axis = 0; axis < 3; ++axis) {
    const int v = vertex[axis];
    std::vector<int> up = faces_along_ray(octree, vertex, axis, +1);
    std::vector<int> down = faces_along_ray(octree, vertex, axis, -1);
    // Extend past the boundary by repeating the last interval; a vertex on the boundary has no interval
    // on that side and repeats the first one of the other side (the domain is at least 2 cells wide
    // whenever max_depth >= 1, and with max_depth = 0 both sides are the one cell's width).
    const int first_up = up.empty() ? (down.empty() ? R : v - down[0]) : up[0] - v;
    const int first_down = down.empty() ? (up.empty() ? R : up[0] - v) : v - down[0];
    while (up.size() < 2) {
      const int last = up.size() == 1 ? up[0] - v : first_up;
      up.push_back((up.empty() ? v : up.back()) + last);
    }
    while (down.size() < 2) {
      const int last = down.size() == 1 ? v - down[0] : first_down;
      down.push_back((down.empty() ? v : down.back()) - last);
    }
    knots[axis] = {down[1], down[0], v, up[0], up[1]};
  }
  return knots;
}

}  // namespace dtsl
