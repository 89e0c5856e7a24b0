// Connected components, in one place: of a mesh's vertices through its faces (the components the
// metrics count and the polygonizer keeps or drops), and of a marked subset of a vertex graph (the
// displacement's holes and fairing regions, docs/design.md §3).
#pragma once

#include <cstddef>
#include <vector>

#include "framework/core/types.hpp"

namespace dtsl {

struct VertexComponents {
  /// Per vertex: its component, 0..count-1, numbered in the order of each component's smallest vertex;
  /// -1 for a vertex no face references.
  std::vector<int> label;
  std::size_t count = 0;
};

/// Components of `vertices` vertices joined through `faces`. Pre-condition: every index in
/// [0, vertices) (mesh_edges / mesh_adjacency check it with a message).
VertexComponents vertex_components(std::size_t vertices, const std::vector<Face>& faces);
VertexComponents vertex_components(const TriangleMesh& mesh);

/// The connected groups of the vertices v with member[v] set, joined through the graph `neighbours`
/// (symmetric, e.g. MeshAdjacency::vertex_neighbours). Groups come in the order of their smallest
/// vertex; each lists its vertices depth-first from that vertex (a stack, neighbours pushed in list
/// order), so whatever solves over a group sees its unknowns in a fixed order.
/// Pre-condition: member.size() == neighbours.size().
std::vector<std::vector<int>> connected_groups(const std::vector<std::vector<int>>& neighbours,
                                               const std::vector<char>& member);

}  // namespace dtsl
