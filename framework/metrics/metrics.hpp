// The metrics of docs/design.md §5, one definition shared by every table. Distances are exact point-triangle
// distances through an AABB tree (CGAL), never nearest-sample distances.
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "framework/core/types.hpp"

namespace dtsl {

/// Exact closest-point queries on a triangle mesh (CGAL AABB tree behind a pimpl).
class MeshDistance {
 public:
  /// Builds the whole tree now, so queries are const and thread-safe. Zero-area faces are left out (no
  /// normal; their points lie on neighbouring edges). Throws AlgorithmError for a mesh without faces,
  /// with every face of zero area, with a vertex index out of range or a non-finite vertex.
  explicit MeshDistance(const TriangleMesh& mesh);
  ~MeshDistance();
  MeshDistance(const MeshDistance&) = delete;
  MeshDistance& operator=(const MeshDistance&) = delete;

  struct Hit {
    double distance;
    Vec3 point;
    int face;
  };
  Hit closest(const Vec3& p) const;  ///< thread-safe; throws AlgorithmError for a non-finite point

  /// closest() of every point, in input order. Runs the queries along a space-filling curve (far
  /// fewer cache misses) and in parallel if built with OpenMP; neither changes any result.
  std::vector<Hit> closest_all(const std::vector<Vec3>& points) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The paper's Eq. 9 errors: mean and max distance from the points to the mesh (frame units; tables
/// report them x 1e3).
struct PointErrors {
  double e_avr = 0.0;
  double e_max = 0.0;
};
/// Throws AlgorithmError for no points, a non-finite point, or a mesh MeshDistance rejects.
PointErrors point_errors(const std::vector<Vec3>& points, const TriangleMesh& mesh);

/// Result R against ground truth G, with `samples` area-uniform samples on each, drawn from two
/// streams fixed by `seed` (deterministic; the thread count never changes a result). "Within tau" is
/// distance <= tau. Throws AlgorithmError naming "result" or "truth" for a mesh MeshDistance rejects,
/// and for samples == 0 or a negative or non-finite tau_ratio.
struct SurfaceMetrics {
  double accuracy = 0.0;            ///< mean distance of R's samples to G
  double completeness = 0.0;        ///< mean distance of G's samples to R
  double chamfer = 0.0;             ///< (accuracy + completeness) / 2
  double hausdorff = 0.0;           ///< max of the two directed maxima
  double normal_consistency = 0.0;  ///< mean |n . n'| with the closest triangle's normal, both ways
  double precision = 0.0;           ///< fraction of R's samples within tau of G
  double recall = 0.0;              ///< fraction of G's samples within tau of R
  double fscore = 0.0;              ///< harmonic mean of precision and recall
  double tau = 0.0;                 ///< the F-score threshold used (tau_ratio x G's bbox diagonal)
};
SurfaceMetrics compare_surfaces(const TriangleMesh& result, const TriangleMesh& truth, std::size_t samples,
                                double tau_ratio, std::uint64_t seed);

/// Combinatorial and quality statistics of a mesh. Topology (edges, fans, components, Euler
/// characteristic) uses the faces with three distinct indices and the vertices they reference; a face
/// with a repeated index is only counted as degenerate. Throws AlgorithmError for an index out of range
/// or a vertex that is not finite; a mesh without faces gives zero counts and NaN angles and genus.
struct MeshStats {
  std::size_t vertices = 0, faces = 0;
  std::size_t boundary_edges = 0, nonmanifold_edges = 0;  ///< edges used by one face / by more than two
  std::size_t nonmanifold_vertices = 0;  ///< vertices whose faces form more than one fan (e.g. a bow tie)
  bool watertight = false;  ///< has faces, no boundary edge, no non-manifold edge or vertex
  std::size_t components = 0;      ///< connected through shared vertices
  int euler_characteristic = 0;    ///< V - E + F over referenced vertices
  double genus = 0.0;  ///< (2 * components - chi) / 2 for a closed mesh; NaN if not watertight
  /// Each triangle's smallest angle: its minimum, 1st percentile (nearest rank) and mean over all faces.
  double min_angle_deg = 0.0, min_angle_p01_deg = 0.0, min_angle_mean_deg = 0.0;
  double valence6_fraction = 0.0;  ///< among referenced vertices on no boundary edge; NaN if none
  std::size_t degenerate_faces = 0;  ///< repeated index, or area zero up to rounding
};
MeshStats mesh_stats(const TriangleMesh& mesh);

nlohmann::json to_json(const PointErrors& e);
nlohmann::json to_json(const SurfaceMetrics& m);
nlohmann::json to_json(const MeshStats& s);

}  // namespace dtsl
