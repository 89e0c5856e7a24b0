// Polygonizers: plugins that turn the zero level set of an implicit function into a triangle mesh (the
// paper's initial mesh M_0, §2.2; docs/design.md §2). Every polygonizer
//  - triangulates each component of {f = 0} that carries data (a seed hint near it) and none twice,
//  - returns a closed, edge-manifold mesh for a closed level set (a level set that leaves f's domain
//    is cut open there, and the summary says so),
//  - gives the mesh vertex normals grad f / |grad f| taken from f, not from the triangles,
//  - reports a summary (counts, time, quality).
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "framework/config/options.hpp"
#include "framework/core/implicit.hpp"
#include "framework/core/types.hpp"
#include "framework/registry/registry.hpp"

namespace dtsl {

/// Triangle-quality numbers of a polygonizer's output: a diagnostic of the stage, the fields of the
/// metrics module's mesh_stats that concern it (one definition, docs/design.md §5).
struct MeshQuality {
  double min_angle_deg = 0.0;       ///< smallest triangle angle in the mesh
  double min_angle_p01_deg = 0.0;   ///< 1st percentile (nearest rank) of the triangles' smallest angles
  double min_angle_mean_deg = 0.0;  ///< mean of the triangles' smallest angles
  double valence6_fraction = 0.0;   ///< vertices of valence 6 among vertices on no boundary edge
  std::size_t boundary_edges = 0;   ///< edges with one triangle (0 for a closed result)
};
/// Throws AlgorithmError for a non-finite vertex or a face index out of range (as mesh_stats).
MeshQuality mesh_quality(const TriangleMesh& mesh);

struct PolygonizeSummary {
  std::string method;
  std::size_t vertices = 0, faces = 0;
  std::size_t components = 0;           ///< level-set components triangulated
  std::size_t seed_candidates = 0;       ///< data foot points (or grid roots when no hint was given)
  std::size_t seed_failures = 0;         ///< hint points whose Newton foot point did not converge
  std::size_t seeds_outside_domain = 0;  ///< foot points outside f's domain (ignored)
  std::size_t dropped_components = 0;    ///< components found but not kept (no data near them, too small)
  std::size_t open_boundaries = 0;       ///< front loops left open where the level set leaves the domain
  double seconds = 0.0;                  ///< wall time of polygonize()
  MeshQuality quality;
  nlohmann::json details = nlohmann::json::object();  ///< method-specific counters (splits, grid size...)
};
nlohmann::json to_json(const MeshQuality& q);
nlohmann::json to_json(const PolygonizeSummary& s);

struct PolygonizeResult {
  TriangleMesh mesh;  ///< indexed, with unit vertex normals from grad f
  PolygonizeSummary summary;
};

class Polygonizer {
 public:
  virtual ~Polygonizer() = default;
  virtual Options& options() = 0;
  /// `seeds_hint`: the data points (frame coordinates). Their Newton foot points on f = 0 decide which
  /// components are meshed (paper §2.2, steps 1-7); with an empty hint every component found is meshed.
  /// Throws ConfigError for invalid options and AlgorithmError when the level set cannot be meshed
  /// (e.g. a front that cannot close, a step too large for the curvature), naming the problem.
  virtual PolygonizeResult polygonize(const ImplicitFunction& f, const std::vector<Vec3>& seeds_hint) = 0;
  /// The same at marching step `step` (frame units) instead of the options' step, which is left as it
  /// is: how a pipeline hands over the step it computed (paper §2.2: delta = 0.2 l_T), as a number.
  /// ConfigError for a step the options' check rejects.
  virtual PolygonizeResult polygonize(const ImplicitFunction& f, const std::vector<Vec3>& seeds_hint, double step) = 0;
};

Registry<Polygonizer>& polygonizers();

/// Adds marching_triangulation and marching_cubes to polygonizers(). Idempotent.
void register_polygonizers();

}  // namespace dtsl
