// Private to algorithms/baselines: the shell shared by the baselines — input validation (counts,
// finiteness, duplicates, degenerate shapes), the normal source, the clean-up of polygon output into a
// TriangleMesh, and the stage records. No PCL or CGAL header here: the library calls live in one .cpp
// per method (poisson.cpp, marching_cubes.cpp, gp3.cpp, grid_projection.cpp, cgal_advancing_front.cpp,
// cgal_scale_space.cpp), pcl_convert.cpp, and external.cpp for a command-line reconstructor.
#pragma once

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "algorithms/normals/normals.hpp"
#include "framework/core/types.hpp"
#include "framework/pipeline/reconstructor.hpp"

namespace dtsl::baselines {

/// What a method needs of its input before PCL (or CGAL, or an external program) may see it.
struct InputRequirements {
  std::size_t min_points = 10;  ///< distinct points (after merging duplicates)
  bool needs_volume = true;     ///< refuse coplanar input: the method builds an inside/outside function
};

/// Principal extents of a point set: square roots of the covariance eigenvalues, largest first.
Vec3 principal_extents(const std::vector<Vec3>& points);

/// Merges points that coincide in single precision (PCL works in float), keeping the first occurrence
/// and its normal. Returns the number of points removed.
std::size_t remove_duplicates(PointCloud& cloud);

/// Validates `cloud` for `method` and returns it without duplicates. Throws AlgorithmError naming the
/// method for: fewer than req.min_points points (given or distinct), NaN/infinite coordinates or
/// normals, a normals array of the wrong length, collinear points, coplanar points if req.needs_volume.
PointCloud validated_input(const std::string& method, const PointCloud& cloud, const InputRequirements& req,
                           std::size_t* duplicates_removed = nullptr);

/// Output of a PCL reconstructor in neutral form: vertices and polygons (any size >= 3).
struct PolygonSoup {
  std::vector<Vec3> vertices;
  std::vector<std::vector<int>> polygons;
};

/// What the clean-up did, for the stage summary.
struct CleanupCounts {
  std::size_t polygons = 0;            ///< polygons PCL returned
  std::size_t triangles = 0;           ///< triangles after fan triangulation, before dropping any
  std::size_t vertices_in = 0;         ///< vertices PCL returned
  std::size_t welded = 0;              ///< vertices merged into an earlier one within the weld tolerance
  std::size_t invalid_dropped = 0;     ///< triangles with an out-of-range index or a non-finite vertex
  std::size_t degenerate_dropped = 0;  ///< triangles with a repeated vertex index
  std::size_t duplicate_dropped = 0;   ///< triangles with the same three vertices as an earlier one
  std::size_t unreferenced_removed = 0;  ///< vertices no kept triangle uses
  nlohmann::json to_json() const;
};

/// Fan-triangulates every polygon (v0, vi, vi+1), optionally welds vertices closer than
/// `weld_tolerance` (0: no welding; PCL's marching cubes and grid projection emit one vertex per face
/// corner), drops triangles with repeated, out-of-range or non-finite vertices and exact duplicates,
/// and removes unreferenced vertices. `flip` reverses every triangle's orientation.
TriangleMesh soup_to_mesh(const PolygonSoup& soup, double weld_tolerance, bool flip, CleanupCounts* counts);

/// The common body of the five baselines: validate, get normals (stage "normals"), run the method
/// (stage "reconstruct"), refuse an empty result. Derived classes hold the options and call PCL.
class PclBaseline : public Reconstructor {
 public:
  ReconstructionResult reconstruct(const PointCloud& points, const RunContext& context) final;

 protected:
  explicit PclBaseline(std::string name) : name_(std::move(name)) {}
  const std::string& name() const { return name_; }

  virtual const NormalSourceOptions& normal_options() const = 0;
  virtual InputRequirements requirements() const = 0;
  /// Refusals that depend on the (deduplicated, validated) input's size or extent, made before the
  /// normals are estimated: e.g. MarchingCubesRBF's point limit, GridProjection's cell count.
  virtual void check_input(const PointCloud& /*cloud*/) const {}
  /// Runs the method on `cloud` (unit normals, one per point, no duplicates). Fills `summary` with its
  /// counts (grid size, clean-up counts, ...). May return a mesh without faces; the caller refuses it.
  virtual TriangleMesh run(const PointCloud& cloud, const RunContext& context, nlohmann::json& summary) = 0;
  /// Appended to the "produced no triangles" error: which options to try.
  virtual std::string empty_hint() const = 0;

 private:
  std::string name_;
};

/// The common body of the baselines that take the points as given (no normal stage): validate, run
/// the method (stage "reconstruct"), refuse an empty result. CGAL's interpolating reconstructors and
/// the external command derive from it.
class PointsBaseline : public Reconstructor {
 public:
  ReconstructionResult reconstruct(const PointCloud& points, const RunContext& context) final;

 protected:
  explicit PointsBaseline(std::string name) : name_(std::move(name)) {}
  const std::string& name() const { return name_; }

  virtual InputRequirements requirements() const = 0;
  /// "normals_source" of the result: "none", or "ground_truth" if the method is given the cloud's normals.
  virtual std::string normals_source() const { return "none"; }
  /// Runs the method on `cloud` (validated, no duplicates); as PclBaseline::run.
  virtual TriangleMesh run(const PointCloud& cloud, const RunContext& context, nlohmann::json& summary) = 0;
  virtual std::string empty_hint() const = 0;

 private:
  std::string name_;
};

/// Stage "reconstruct" of either shell: times `run`, refuses a mesh without faces (AlgorithmError naming
/// `method`, the point count and `hint`), records the mesh's counts in the summary.
StageRecord reconstruct_stage(const std::string& method, std::size_t points,
                              const std::function<TriangleMesh(nlohmann::json&)>& run,
                              const std::function<std::string()>& hint, TriangleMesh& mesh);

/// Reverses every triangle if the mesh encloses a negative signed volume about `centre`: CGAL's
/// interpolating meshes are consistently oriented per component but not necessarily outward.
/// Returns whether it flipped.
bool orient_outward(TriangleMesh& mesh, const Vec3& centre);

// Factories of the registered baselines (one .cpp each; registration in baselines.cpp).
std::unique_ptr<Reconstructor> make_pcl_poisson();
std::unique_ptr<Reconstructor> make_pcl_mc_hoppe();
std::unique_ptr<Reconstructor> make_pcl_mc_rbf();
std::unique_ptr<Reconstructor> make_pcl_gp3();
std::unique_ptr<Reconstructor> make_pcl_grid();
std::unique_ptr<Reconstructor> make_cgal_advancing_front();
std::unique_ptr<Reconstructor> make_cgal_scale_space();
std::unique_ptr<Reconstructor> make_external();

/// Runs `body` (a PCL call) and turns std::bad_alloc and other std::exceptions into AlgorithmError
/// naming `method`.
template <class F>
void guarded_pcl_call(const std::string& method, F&& body);

std::string format_number(double value);

// ---- implementation of the template ------------------------------------------------------------

/// Inside a catch block: rethrows dtsl's own errors, and turns the current exception into an
/// AlgorithmError naming `method` and `library` (with `memory_hint` for std::bad_alloc).
[[noreturn]] void rethrow_library_failure(const std::string& method, const std::string& library,
                                          const std::string& memory_hint);
[[noreturn]] void rethrow_pcl_failure(const std::string& method);

template <class F>
void guarded_pcl_call(const std::string& method, F&& body) {
  try {
    body();
  } catch (...) {
    rethrow_pcl_failure(method);
  }
}

}  // namespace dtsl::baselines
