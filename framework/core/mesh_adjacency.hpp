// The connectivity of an indexed triangle mesh, built once and shared by every stage that walks a mesh:
// the displacement's closest-point search and graph solves (paper §3.1), the sharpening's one-rings
// (§4.2, Eq. 8), the polygonizers' and the metrics' edge counts.
//
// An own structure, not CGAL::Surface_mesh: a halfedge mesh rejects a face on an edge that already has
// two (Surface_mesh::add_face returns null_face), and the meshes measured here may have such edges,
// bow-tie vertices, boundaries and faces with a repeated corner (baselines' outputs, displaced meshes);
// the statistics must count them, not fail on them. Positions may change without rebuilding.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "framework/core/types.hpp"

namespace dtsl {

/// The undirected edges of the faces with three distinct corners, each with the faces around it. A
/// face with a repeated corner has no area and no orientation to share: it is no edge's face.
struct MeshEdges {
  std::vector<std::array<int, 2>> ends;  ///< (u, v) with u < v, sorted ascending
  std::vector<std::size_t> first_face;   ///< edge e's faces: faces[first_face[e] .. first_face[e + 1])
  std::vector<int> faces;                ///< face indices, ascending within an edge

  std::size_t size() const { return ends.size(); }
  std::size_t face_count(std::size_t e) const { return first_face[e + 1] - first_face[e]; }
  /// An edge of one face: on the mesh's boundary.
  bool boundary(std::size_t e) const { return face_count(e) == 1; }
  /// An edge of three or more faces: no surface is a manifold there.
  bool nonmanifold(std::size_t e) const { return face_count(e) > 2; }
  /// Distinct edges at each of `vertices` vertices (its valence).
  std::vector<int> valences(std::size_t vertices) const;
  /// 1 for a vertex on a boundary edge.
  std::vector<char> boundary_vertices(std::size_t vertices) const;
};

/// Rings and fans of every vertex, and the edges.
struct MeshAdjacency {
  /// Faces at each vertex, ascending, once per corner (a face with a repeated corner twice).
  std::vector<std::vector<int>> vertex_faces;
  /// Vertices sharing a face side with each vertex, sorted, without repeats (a face's repeated corner
  /// makes a vertex its own neighbour).
  std::vector<std::vector<int>> vertex_neighbours;
  MeshEdges edges;
};

/// Throws AlgorithmError "<what>: face F has vertex index I out of range (N vertices)".
MeshEdges mesh_edges(const TriangleMesh& mesh, const std::string& what = "mesh");
/// The same check and message as mesh_edges.
MeshAdjacency mesh_adjacency(const TriangleMesh& mesh, const std::string& what = "mesh");
/// MeshAdjacency::vertex_faces alone (for a search that needs no rings); the same check and message.
std::vector<std::vector<int>> vertex_faces(const TriangleMesh& mesh, const std::string& what = "mesh");

/// Edges two of whose faces traverse them the same way, so the faces' orientations disagree there (0 on
/// a consistently oriented mesh). Pre-condition: `edges` is mesh_edges(mesh).
std::size_t misoriented_edges(const TriangleMesh& mesh, const MeshEdges& edges);

/// Vertices within `rings` edge hops of v (v included), in breadth-first order.
std::vector<int> k_ring(const MeshAdjacency& adjacency, int v, int rings);

}  // namespace dtsl
