// One-ring adjacency of an indexed triangle mesh: what sharp-vertex detection (one-ring dihedral angles,
// paper §4.2), the bilateral target (neighbouring triangles N(v), Eq. 8) and the foot-point cases
// (Fig. 2) need. Built once per mesh connectivity; positions may change without rebuilding it.
#pragma once

#include <vector>

#include "framework/core/types.hpp"

namespace dtsl::sharpen {

struct MeshAdjacency {
  std::vector<std::vector<int>> vertex_faces;      ///< faces incident to each vertex
  std::vector<std::vector<int>> vertex_neighbors;  ///< vertices sharing an edge with each vertex, sorted
};

/// Throws AlgorithmError for a face index out of range.
MeshAdjacency build_adjacency(const TriangleMesh& mesh);

/// Vertices within `rings` edge hops of v (v included), in BFS order.
std::vector<int> k_ring(const MeshAdjacency& adj, int v, int rings);

}  // namespace dtsl::sharpen
