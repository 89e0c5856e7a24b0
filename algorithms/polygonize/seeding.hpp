// Choosing where to start, and knowing what is already meshed: the paper's seven-step seeding (§2.2).
//   1. project every data point p_k onto f = 0 (Newton): foot points q_k;
//   2. the potential seeds P = {q_k};  3. M = {};
//   4. pick a seed in P, march a mesh M_i from it, add M_i to M;
//   5. drop from P every q_k whose distance to M_i is small (closest vertex, then its neighbourhood's
//      triangles, as in §3.1 Fig. 2);
//   6. repeat 4-5 until P is empty;  7. output M.
// Every component carrying data thus gets a seed, and no component is marched twice (its foot points
// are all gone after its first march). Without data, sign changes of f on a grid give the seeds.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "algorithms/polygonize/newton_projection.hpp"
#include "algorithms/polygonize/spatial_hash.hpp"
#include "framework/core/implicit.hpp"
#include "framework/core/types.hpp"

namespace dtsl {

/// Points on f = 0 to start from, with the accounting of those that could not be used.
struct SeedCandidates {
  std::vector<Vec3> points;          ///< on f = 0, inside f's domain
  std::size_t candidates = 0;        ///< points tried
  std::size_t failures = 0;          ///< Newton did not converge
  std::size_t outside_domain = 0;    ///< converged outside f's domain
};

/// Steps 1-2: the Newton foot points of the data points (OpenMP-parallel).
SeedCandidates foot_point_seeds(const ImplicitFunction& f, const std::vector<Vec3>& data,
                                const NewtonOptions& newton);

/// Seeds without data: a root of f on every grid edge (spacing `spacing` over `box`) where f changes
/// sign, projected by Newton. Finds every component that crosses a grid edge, so components smaller
/// than the spacing may be missed.
SeedCandidates grid_seeds(const ImplicitFunction& f, const BoundingBox& box, double spacing,
                          const NewtonOptions& newton);

/// Distances from points near a triangle mesh to it: candidate triangles are those around the mesh
/// vertices within `radius` of the query (the paper's closest-vertex one-ring, §3.1, widened to all
/// vertices in the ball so a slightly irregular mesh cannot hide the closest triangle).
class MeshProximity {
 public:
  MeshProximity(const TriangleMesh& mesh, double radius);
  struct Hit {
    double distance;  ///< infinity if no vertex lies within `radius`
    int face;         ///< -1 then
  };
  Hit closest(const Vec3& p) const;

 private:
  const TriangleMesh& mesh_;
  double radius_;
  SpatialHash hash_;
  std::vector<std::vector<int>> vertex_faces_;
};

/// Exact distance from p to triangle (a, b, c) (closest point by Voronoi regions).
double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// What one march from a seed produced. `skipped` marks a seed that could not start a march (e.g. a
/// component smaller than the step): the seeds near it are then dropped as well.
struct ComponentMesh {
  TriangleMesh mesh;
  bool skipped = false;
};

struct SeededMeshing {
  TriangleMesh mesh;                  ///< all components, concatenated
  std::size_t components = 0;         ///< marched components
  std::size_t skipped_seeds = 0;      ///< seeds that could not start a march
  std::size_t duplicates = 0;         ///< marches that meshed a kept component again, dropped
};

/// Steps 3-7 over `seeds` (already on f = 0). A seed is covered by a component when its distance to
/// that component's mesh is below `cover_distance`; a skipped seed drops the seeds within
/// `skip_radius` of it. `proximity_radius` bounds the vertex search of the distance test (about twice
/// the mesh's edge length). A march whose mesh lies mostly within half `proximity_radius` (about an
/// edge) of the components kept so far meshed one of them again (from a seed farther than
/// `cover_distance` from its triangles): it is dropped, with the seeds it covers. Throws AlgorithmError
/// when more than `max_components` are started.
SeededMeshing mesh_from_seeds(const std::vector<Vec3>& seeds, double cover_distance, double proximity_radius,
                              double skip_radius, std::size_t max_components,
                              const std::function<ComponentMesh(const Vec3& seed)>& march);

/// Appends `part` (vertices, faces, normals) to `mesh`.
void append_mesh(TriangleMesh& mesh, const TriangleMesh& part);

}  // namespace dtsl
