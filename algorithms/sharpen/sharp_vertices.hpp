// Sharp-vertex detection (paper §4.2): only vertices with both a high dihedral angle and a large local
// fitting error move during the bilateral evolution; all others keep v' = 0.
//
// Potential sharp vertices follow the paper's ref [53] (Wang 2006): a vertex whose one-ring contains an
// edge with a dihedral angle (angle between the two face normals) above a threshold. A displaced mesh,
// however, is smooth: its edges are rounded over a few triangles, so no single dihedral angle need be
// large. We therefore also accept a vertex whose normal differs from the normal of some triangle within
// `normal_variation_rings` edge hops by more than `normal_variation_deg` (a normal-variation measure over
// a slightly larger neighbourhood that sees the whole rounded strip). A potential sharp vertex is kept
// only if its one-ring is badly fitted: the data points whose foot points lie on its one-ring faces are,
// on average, farther than `error_ratio` x e_avr (Eq. 9, all data) from the mesh.
#pragma once

#include <cstddef>
#include <vector>

#include "algorithms/sharpen/foot_points.hpp"
#include "framework/core/mesh_adjacency.hpp"
#include "framework/config/options.hpp"

namespace dtsl::sharpen {

struct SharpVertexOptions final : Options {
  /// One-ring dihedral angle (degrees) above which a vertex is a potential sharp vertex (ref [53]).
  double dihedral_angle_deg = 25.0;
  /// Angle (degrees) between the vertex normal and a triangle normal within normal_variation_rings
  /// above which a vertex is also a potential sharp vertex (rounded edges of a displaced mesh); 0: off.
  double normal_variation_deg = 30.0;
  /// Edge hops of the neighbourhood the normal variation looks at.
  int normal_variation_rings = 2;
  /// Keep a potential sharp vertex only if the mean distance of the data whose foot points lie on its
  /// one-ring exceeds error_ratio x e_avr (the already well-fitted vertices are discarded, paper §4.2).
  double error_ratio = 1.5;
  /// ...and at least this many data points have their foot points there (no evidence, no move).
  int min_points = 1;

  void visit(FieldVisitor& v) override;
  void check() const override;
};

struct SharpVertices {
  std::vector<int> vertices;      ///< the real sharp vertices, ascending
  std::size_t potential = 0;      ///< potential sharp vertices (angle criteria) before the error filter
  std::size_t by_dihedral = 0;    ///< of those, found by the one-ring dihedral angle
};

/// Area-weighted unit vertex normals of the current positions.
std::vector<Vec3> vertex_normals(const TriangleMesh& mesh, const MeshAdjacency& adj);

/// `feet` are the foot points of all data on `mesh` (their mean distance is e_avr).
SharpVertices detect_sharp_vertices(const TriangleMesh& mesh, const MeshAdjacency& adj,
                                    const std::vector<FootPoint>& feet, const SharpVertexOptions& options);

}  // namespace dtsl::sharpen
