// One run: a pipeline on a dataset, its meshes written, its metrics measured (DESIGN.md §5). The same
// function serves `dtsl run` (in a child process per run) and the tests.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "framework/datasets/dataset.hpp"
#include "framework/pipeline/experiment.hpp"

namespace dtsl {

/// Runs `run` on `dataset`, writes final.ply, one stage_<label>.ply per stage mesh and one <name>.obj per
/// stage line set (StageLines: the T-mesh) into `run_dir`, each atomically, and returns the metrics
/// record (status "ok", or "failed" with the error message: a failed run is a result, not a crash).
/// Never throws for errors of the pipeline itself.
nlohmann::json execute_run(const RunSpec& run, const Dataset& dataset, const MetricsOptions& metrics,
                           std::uint64_t seed, const std::string& run_dir);

/// The errors, mesh statistics and (with a ground truth) surface metrics of `mesh`.
nlohmann::json measure_mesh(const TriangleMesh& mesh, const Dataset& dataset, const MetricsOptions* metrics,
                            std::uint64_t seed);

}  // namespace dtsl
