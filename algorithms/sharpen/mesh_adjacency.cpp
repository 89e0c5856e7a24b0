#include "algorithms/sharpen/mesh_adjacency.hpp"

#include <algorithm>
#include <string>

#include "framework/core/error.hpp"

namespace dtsl::sharpen {

MeshAdjacency build_adjacency(const TriangleMesh& mesh) {
  const int n = static_cast<int>(mesh.vertices.size());
  MeshAdjacency adj;
  adj.vertex_faces.resize(n);
  adj.vertex_neighbors.resize(n);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& t = mesh.faces[f];
    for (int c = 0; c < 3; ++c) {
      if (t[c] < 0 || t[c] >= n)
        throw AlgorithmError("mesh face " + std::to_string(f) + " has vertex index " + std::to_string(t[c]) +
                             " out of range (" + std::to_string(n) + " vertices)");
    }
    for (int c = 0; c < 3; ++c) {
      adj.vertex_faces[t[c]].push_back(static_cast<int>(f));
      adj.vertex_neighbors[t[c]].push_back(t[(c + 1) % 3]);
      adj.vertex_neighbors[t[c]].push_back(t[(c + 2) % 3]);
    }
  }
  for (auto& nb : adj.vertex_neighbors) {
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
  }
  return adj;
}

std::vector<int> k_ring(const MeshAdjacency& adj, int v, int rings) {
  std::vector<int> out{v};
  std::size_t begin = 0;
  for (int r = 0; r < rings; ++r) {
    const std::size_t end = out.size();
    for (std::size_t i = begin; i < end; ++i)
      for (const int w : adj.vertex_neighbors[out[i]])
        if (std::find(out.begin(), out.end(), w) == out.end()) out.push_back(w);
    begin = end;
  }
  return out;
}

}  // namespace dtsl::sharpen
