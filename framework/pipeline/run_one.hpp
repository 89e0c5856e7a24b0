// One run: a pipeline on a dataset, its meshes written, its metrics measured (docs/design.md §5). The same
// function serves `dtsl run` (in a child process per run) and the tests.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "framework/datasets/dataset.hpp"
#include "framework/pipeline/dataset_cache.hpp"
#include "framework/pipeline/experiment.hpp"
#include "framework/pipeline/reconstructor.hpp"

namespace dtsl {

/// Runs `run` on `dataset`, writes final.ply, one stage_<label>.ply per stage mesh and one <name>.obj per
/// stage line set (StageLines: the T-mesh) into `run_dir` in `frame`, each atomically, and returns the
/// metrics record (measured in the [-1,1]^3 frame; status "ok", or "failed" with the error message: a
/// failed run is a result, not a crash). Never throws for errors of the pipeline itself.
nlohmann::json execute_run(const RunSpec& run, const Dataset& dataset, const MetricsOptions& metrics,
                           std::uint64_t seed, const std::string& run_dir, FilesFrame frame);

/// Writes `result`'s stage meshes (stage_<label>.ply) and line sets (<name>.obj) into `dir`, each
/// atomically, and returns a record per stage: name, seconds, summary and the files written. Throws
/// AlgorithmError for a line set whose name is not a plain file stem.
nlohmann::json write_stage_files(const ReconstructionResult& result, const std::string& dir);

/// The errors, mesh statistics and (with a ground truth) surface metrics of `mesh`.
nlohmann::json measure_mesh(const TriangleMesh& mesh, const Dataset& dataset, const MetricsOptions* metrics,
                            std::uint64_t seed);

}  // namespace dtsl
