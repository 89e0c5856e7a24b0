#include "algorithms/polygonize/overlapping_sheets.hpp"

#include <unordered_map>
#include <vector>

#include "algorithms/polygonize/spatial_hash.hpp"
#include "framework/core/mesh_adjacency.hpp"

namespace dtsl {

namespace {

// Whether `target` is within `max_hops` edges of `source` (a breadth-first search that stops there).
bool within_hops(const std::vector<std::vector<int>>& neighbours, int source, int target, int max_hops) {
  std::unordered_map<int, int> hops{{source, 0}};
  std::vector<int> frontier{source}, next;
  for (int h = 1; h <= max_hops && !frontier.empty(); ++h) {
    next.clear();
    for (int v : frontier)
      for (int u : neighbours[static_cast<std::size_t>(v)]) {
        if (u == target) return true;
        if (hops.emplace(u, h).second) next.push_back(u);
      }
    frontier.swap(next);
  }
  return false;
}

}  // namespace

std::optional<Vec3> overlapping_sheets(const TriangleMesh& mesh, double radius, int max_hops) {
  if (!mesh.has_normals() || mesh.faces.empty()) return std::nullopt;
  const std::vector<std::vector<int>> neighbours = mesh_adjacency(mesh, "overlapping_sheets").vertex_neighbours;
  SpatialHash hash(radius);
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) hash.insert(static_cast<int>(v), mesh.vertices[v]);
  const double r2 = radius * radius;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    std::optional<Vec3> found;
    hash.for_each_near(mesh.vertices[v], radius, [&](int u) {
      if (found || u <= static_cast<int>(v)) return;  // each pair once
      if ((mesh.vertices[static_cast<std::size_t>(u)] - mesh.vertices[v]).squaredNorm() > r2) return;
      if (mesh.normals[static_cast<std::size_t>(u)].dot(mesh.normals[v]) < 0.5) return;  // a thin wall's other side
      if (!within_hops(neighbours, static_cast<int>(v), u, max_hops)) found = mesh.vertices[v];
    });
    if (found) return found;
  }
  return std::nullopt;
}

}  // namespace dtsl
