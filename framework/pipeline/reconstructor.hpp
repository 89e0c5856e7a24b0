// A reconstructor takes points (in the [-1,1]^3 frame, normals optional) and returns a mesh plus a record
// of its stages. The paper's method and every baseline are reconstructors, so one experiment compares
// them on the same data, measured the same way.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "framework/config/options.hpp"
#include "framework/core/types.hpp"
#include "framework/registry/registry.hpp"

namespace dtsl {

/// Line geometry a stage leaves for figures, e.g. the edges of the T-mesh's cells (the paper's Fig. 1a).
struct StageLines {
  std::string name;   ///< the file's stem in the run directory ("tmesh" -> tmesh.obj); letters, digits, '_', '-'
  std::string label;  ///< how figures name it ("T-mesh")
  std::vector<std::array<Vec3, 2>> segments;  ///< end points, in the frame of the meshes
};

/// One stage of a reconstruction: its short name (the paper's Table 1 uses TL, MT, D-Map, B-Evl), wall
/// time, the mesh it produced if any (written out and measured like the final one), and a free-form
/// summary (counts, convergence history).
struct StageRecord {
  std::string name;
  double seconds = 0.0;
  std::optional<TriangleMesh> mesh;
  std::string mesh_label;  ///< e.g. "MI", "MD", "MS": the column label of this stage's mesh errors
  nlohmann::json summary = nlohmann::json::object();
  std::optional<StageLines> lines;  ///< written as <name>.obj next to the stage meshes (`l` records)
};

struct ReconstructionResult {
  TriangleMesh mesh;                ///< the final mesh
  std::vector<StageRecord> stages;  ///< in execution order
  nlohmann::json summary = nlohmann::json::object();  ///< e.g. {"normals_source": "ground_truth"}
};

/// The stage of `result` named `name` (e.g. "MT"), the first if several are. Error naming `name` and
/// the stages there are when none is.
StageRecord& stage(ReconstructionResult& result, const std::string& name);
const StageRecord& stage(const ReconstructionResult& result, const std::string& name);

/// What a run gives a reconstructor besides the points.
struct RunContext {
  std::uint64_t seed = 1;
  int threads = 1;
  /// Called as each stage starts, with its short name (TL, MT, ...) and what it does, for progress
  /// displays; may be empty. Reconstructors without stages never call it.
  std::function<void(const std::string& stage, const std::string& what)> on_stage;
  void stage_started(const std::string& stage, const std::string& what) const {
    if (on_stage) on_stage(stage, what);
  }
};

/// Maps the final mesh, every stage mesh and every stage line set by `s` (into or out of the [-1,1]^3
/// frame).
void transform(ReconstructionResult& result, const Similarity& s);

class Reconstructor {
 public:
  virtual ~Reconstructor() = default;
  virtual Options& options() = 0;
  /// The fewest points reconstruct() accepts, checked by callers before any work: 4 (a tetrahedron's
  /// worth) unless a reconstructor needs more.
  virtual std::size_t minimum_points() const { return 4; }
  /// Throws AlgorithmError for input it cannot handle (too few points, too large, no normals where
  /// they are required), naming the problem.
  virtual ReconstructionResult reconstruct(const PointCloud& points, const RunContext& context) = 0;
};

Registry<Reconstructor>& reconstructors();

}  // namespace dtsl
