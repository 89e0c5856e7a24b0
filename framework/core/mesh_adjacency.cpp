#include "framework/core/mesh_adjacency.hpp"

#include <algorithm>
#include <cstdint>
#include <utility>

#include "framework/core/error.hpp"

namespace dtsl {

namespace {

void check_indices(const TriangleMesh& mesh, const std::string& what) {
  const long n = static_cast<long>(mesh.vertices.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (const int i : mesh.faces[f])
      if (i < 0 || i >= n)
        throw AlgorithmError(what + ": face " + std::to_string(f) + " has vertex index " + std::to_string(i) +
                             " out of range (" + std::to_string(n) + " vertices)");
}

bool repeated_corner(const Face& t) { return t[0] == t[1] || t[1] == t[2] || t[0] == t[2]; }

MeshEdges edges_of(const TriangleMesh& mesh) {
  // Every (edge, face) once, sorted, so the faces around an edge are contiguous and ascending.
  std::vector<std::pair<std::uint64_t, int>> uses;
  uses.reserve(3 * mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& t = mesh.faces[f];
    if (repeated_corner(t)) continue;
    for (int k = 0; k < 3; ++k) {
      const auto [u, v] = std::minmax(t[k], t[(k + 1) % 3]);
      uses.emplace_back((static_cast<std::uint64_t>(u) << 32) | static_cast<std::uint32_t>(v), static_cast<int>(f));
    }
  }
  std::sort(uses.begin(), uses.end());
  MeshEdges e;
  e.faces.reserve(uses.size());
  for (std::size_t i = 0; i < uses.size(); ++i) {
    if (i == 0 || uses[i].first != uses[i - 1].first) {
      e.first_face.push_back(i);
      e.ends.push_back({static_cast<int>(uses[i].first >> 32), static_cast<int>(uses[i].first & 0xffffffffu)});
    }
    e.faces.push_back(uses[i].second);
  }
  e.first_face.push_back(uses.size());
  return e;
}

}  // namespace

std::vector<int> MeshEdges::valences(std::size_t vertices) const {
  std::vector<int> valence(vertices, 0);
  for (const auto& uv : ends) ++valence[uv[0]], ++valence[uv[1]];
  return valence;
}

std::vector<char> MeshEdges::boundary_vertices(std::size_t vertices) const {
  std::vector<char> on(vertices, 0);
  for (std::size_t e = 0; e < size(); ++e)
    if (boundary(e)) on[ends[e][0]] = on[ends[e][1]] = 1;
  return on;
}

MeshEdges mesh_edges(const TriangleMesh& mesh, const std::string& what) {
  check_indices(mesh, what);
  return edges_of(mesh);
}

std::vector<std::vector<int>> vertex_faces(const TriangleMesh& mesh, const std::string& what) {
  check_indices(mesh, what);
  std::vector<std::vector<int>> fans(mesh.vertices.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (const int v : mesh.faces[f]) fans[v].push_back(static_cast<int>(f));
  return fans;
}

MeshAdjacency mesh_adjacency(const TriangleMesh& mesh, const std::string& what) {
  MeshAdjacency adj;
  adj.vertex_faces = vertex_faces(mesh, what);
  adj.vertex_neighbours.resize(mesh.vertices.size());
  for (const Face& t : mesh.faces)
    for (int c = 0; c < 3; ++c) {
      adj.vertex_neighbours[t[c]].push_back(t[(c + 1) % 3]);
      adj.vertex_neighbours[t[c]].push_back(t[(c + 2) % 3]);
    }
  for (auto& ring : adj.vertex_neighbours) {
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  }
  adj.edges = edges_of(mesh);
  return adj;
}

std::size_t misoriented_edges(const TriangleMesh& mesh, const MeshEdges& edges) {
  // +1 where face f runs u -> v, -1 where it runs v -> u.
  const auto direction = [&mesh](int f, int u, int v) {
    const Face& t = mesh.faces[f];
    for (int k = 0; k < 3; ++k)
      if (t[k] == u) return t[(k + 1) % 3] == v ? 1 : -1;
    return 0;
  };
  std::size_t count = 0;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    int forward = 0, backward = 0;
    for (std::size_t i = edges.first_face[e]; i < edges.first_face[e + 1]; ++i)
      (direction(edges.faces[i], edges.ends[e][0], edges.ends[e][1]) > 0 ? forward : backward) += 1;
    count += forward > 1 || backward > 1 ? 1 : 0;
  }
  return count;
}

std::vector<int> k_ring(const MeshAdjacency& adjacency, int v, int rings) {
  std::vector<int> out{v};
  std::size_t begin = 0;
  for (int r = 0; r < rings; ++r) {
    const std::size_t end = out.size();
    for (std::size_t i = begin; i < end; ++i)
      for (const int w : adjacency.vertex_neighbours[out[i]])
        if (std::find(out.begin(), out.end(), w) == out.end()) out.push_back(w);
    begin = end;
  }
  return out;
}

}  // namespace dtsl
