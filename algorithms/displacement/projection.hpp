// Phase 2, step 1: projection of the data onto the initial mesh M_0 (paper §3.1, steps 1-4; docs/design.md §3).
// Each data point p_k gets its Newton foot point q_k on f = 0 (reusing the polygonizers' newton_project),
// the signed displacement d_k = sign(f(p_k)) |p_k - q_k|, and the closest triangle(s) of M_0 to q_k found
// through the one-ring of the closest vertex: no ray casting (paper §3.1, "we do not compute any
// ray-triangle intersections"). A foot point on a vertex or an edge is associated with every triangle
// sharing it (the paper's Fig. 2: face, edge and vertex cases).
//
// MeshLocator is the f-free half: it projects any point onto a triangle mesh through the closest
// vertex's one-ring, so Phase 3 (bilateral evolution) can reuse it on meshes that have left f = 0.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "algorithms/displacement/vertex_grid.hpp"
#include "algorithms/polygonize/newton_projection.hpp"
#include "framework/config/options.hpp"
#include "framework/core/implicit.hpp"
#include "framework/core/mesh_adjacency.hpp"
#include "framework/core/types.hpp"

namespace dtsl {

/// Where the closest point of a triangle lies (paper Fig. 2). `none`: not located (Newton failed).
enum class ProjectionCase { none, vertex, edge, face };
const char* to_string(ProjectionCase c);

/// The closest point of one query on the mesh.
struct MeshLocation {
  int face = -1;                        ///< a closest triangle (the one whose barycentrics are given)
  Vec3 barycentric = Vec3::Zero();      ///< of the closest point w.r.t. faces[face]'s corners, sum 1
  ProjectionCase kind = ProjectionCase::none;
  /// Vertex case: the mesh vertex; edge case: the edge's two vertices (sorted); face case: unused (-1).
  int element[2] = {-1, -1};
  Vec3 point = Vec3::Zero();            ///< the closest point on the mesh
  double distance = 0.0;                ///< |query - point|
  int closest_vertex = -1;              ///< the vertex whose one-ring was searched
  bool found() const { return face >= 0; }
};

struct LocatorOptions final : Options {
  /// Grid cell for the closest-vertex search, x the mean edge length (about one vertex per cell).
  double grid_cell = 1.0;
  /// A barycentric coordinate below this counts as 0, so a closest point within rounding of an edge or
  /// vertex is given the edge / vertex case (and all its triangles).
  double snap_tolerance = 1e-9;

  void visit(FieldVisitor& v) override;
  void check() const override;
};

/// Closest-point queries on a fixed triangle mesh through the closest vertex's one-ring.
///
/// Limits (the price of avoiding ray casting / an AABB tree): the true closest triangle need not be in
/// the closest vertex's one-ring when triangles are very anisotropic, or when the query is far from the
/// mesh compared with the edge length (e.g. across a thin part). On a semi-regular marching mesh and for
/// foot points on the surface it is (paper §3.1); for the data points themselves it is an approximation.
/// locate_from() walks the vertex graph greedily from a guess (Phase 3: the previous closest vertex); it
/// stops at a local minimum of the vertex distance, so a guess more than a few rings away, or a mesh
/// that folds back within that distance, can end at a wrong sheet.
class MeshLocator {
 public:
  /// Throws AlgorithmError for a mesh without faces, a face index out of range or a non-finite vertex.
  explicit MeshLocator(const TriangleMesh& mesh, const LocatorOptions& options = {});

  /// Closest point via the closest vertex (grid search) and its one-ring.
  MeshLocation locate(const Vec3& q) const;
  /// Closest point via a greedy walk from vertex `guess` to a local minimum, then its one-ring.
  MeshLocation locate_from(const Vec3& q, int guess) const;

  /// Every triangle the location belongs to: both triangles of an edge, the whole fan of a vertex.
  std::vector<int> closest_faces(const MeshLocation& loc) const;

  const TriangleMesh& mesh() const { return *mesh_; }
  const MeshAdjacency& adjacency() const { return adjacency_; }
  const std::vector<int>& vertex_faces(int v) const { return adjacency_.vertex_faces[v]; }
  const std::vector<int>& vertex_neighbours(int v) const { return adjacency_.vertex_neighbours[v]; }
  /// Every vertex's neighbours at once (for the graph solves of the hole fill and fairing).
  const std::vector<std::vector<int>>& vertex_neighbours() const { return adjacency_.vertex_neighbours; }
  double mean_edge_length() const { return mean_edge_; }

 private:
  MeshLocation one_ring(const Vec3& q, int vertex) const;

  const TriangleMesh* mesh_;
  LocatorOptions options_;
  MeshAdjacency adjacency_;
  double mean_edge_ = 0.0;
  PointGrid grid_;
};

/// Closest point of triangle (a, b, c) to q with its barycentric coordinates (Ericson, Real-Time
/// Collision Detection §5.1.5): the Voronoi region decides, so a coordinate is exactly 0 off the face.
Vec3 closest_point_on_triangle(const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& barycentric);

struct ProjectionOptions final : Options {
  /// Newton foot points (paper §3.1 step 3.2): stop when |f|/|grad f| is below this (frame units).
  double newton_tolerance = 1e-10;
  /// Newton iteration cap; a point that has not converged is left out of the displacement field.
  int newton_max_iterations = 50;
  /// Longest Newton step, x the mesh's mean edge length (0 = unclamped, the paper's step): keeps far
  /// points (outliers) from jumping to another sheet of f = 0.
  double newton_max_step = 0.0;
  LocatorOptions locator;

  void visit(FieldVisitor& v) override;
  void check() const override;
};

/// The paper's §3.1 output: (I_i) per triangle and (d_k) per point, with the foot points and locations.
struct ProjectionResult {
  std::vector<Vec3> foot_points;         ///< q_k on f = 0
  std::vector<Vec3> foot_normals;        ///< grad f / |grad f| at q_k
  std::vector<double> displacements;     ///< d_k = sign(f(p_k)) |p_k - q_k|
  std::vector<char> valid;               ///< Newton converged and q_k located
  std::vector<MeshLocation> locations;   ///< per point: triangle, barycentrics, case
  std::vector<std::vector<int>> triangle_points;  ///< I_i: the points associated with triangle i
  std::size_t newton_failures = 0;       ///< points whose Newton iteration failed (valid = 0)
  std::size_t cases[4] = {0, 0, 0, 0};   ///< counts indexed by ProjectionCase
  double seconds = 0.0;
  nlohmann::json summary() const;
};

/// Paper §3.1 steps 1-4 for every point (OpenMP-parallel). Throws AlgorithmError for no points, a
/// non-finite point, or a mesh MeshLocator rejects; ConfigError for invalid options.
ProjectionResult project_data(const ImplicitFunction& f, const MeshLocator& locator, const std::vector<Vec3>& points,
                              const ProjectionOptions& options = {});

}  // namespace dtsl
