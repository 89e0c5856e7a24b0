// Foot points q_k of the data on the current mesh and the vertices they depend on (paper Eq. 6 and
// Fig. 2): q_k moves with the 1, 2 or 3 vertices of the mesh element it lies in, with its barycentric
// coordinates as the coefficients lambda_j. Closest points are exact (metrics' MeshDistance, a CGAL
// AABB tree), so no ray casting is involved.
#pragma once

#include <array>
#include <vector>

#include "framework/core/types.hpp"

namespace dtsl::sharpen {

struct FootPoint {
  Vec3 q;          ///< closest point on the mesh
  double distance; ///< |p_k - q_k|
  int face;        ///< the face the closest point was found on
  int count;       ///< 1: at a vertex (Fig. 2a), 2: on an edge (2b), 3: inside a face (2c)
  std::array<int, 3> vertices;   ///< the first `count` entries are used
  std::array<double, 3> lambda;  ///< barycentric weights of those vertices, summing to 1
};

/// Foot point of every point in input order. A barycentric coordinate below `snap` (relative) is
/// treated as zero and the others renormalised, which sorts each foot point into its Fig. 2 case.
/// Throws AlgorithmError for a mesh MeshDistance rejects or a non-finite point.
std::vector<FootPoint> foot_points(const TriangleMesh& mesh, const std::vector<Vec3>& points, double snap);

/// foot_points(after, points, snap), given feet = foot_points(before, points, snap) and a mesh `after`
/// with before's faces whose vertices moved only in part (`vertex_faces`: the faces at each vertex). A
/// point whose foot lies on a face none of whose vertices moved keeps it unless a moved face is now
/// closer (checked on those faces alone, and only for points within their own foot's distance of one);
/// a point whose foot's face moved is searched among the moved faces and the unchanged faces within that
/// distance of it. Each evolution step moves only the sharp vertices, so this saves most of the
/// closest-point queries and the search tree of the whole mesh. The same distances as foot_points; where
/// two faces are equally close (a foot on their common edge or vertex) it may keep the other one.
/// AlgorithmError when the faces differ or the sizes do not match.
std::vector<FootPoint> update_foot_points(const TriangleMesh& before, const TriangleMesh& after,
                                          const std::vector<std::vector<int>>& vertex_faces,
                                          const std::vector<FootPoint>& feet, const std::vector<Vec3>& points,
                                          double snap);

/// Barycentric coordinates of q in triangle (a, b, c) (least squares for a point slightly off it).
std::array<double, 3> barycentric(const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c);

/// Eq. 9: mean of the foot-point distances.
double mean_distance(const std::vector<FootPoint>& feet);

}  // namespace dtsl::sharpen
