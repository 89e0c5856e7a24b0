// `dtsl run`: prepares the datasets of an experiment, runs every (dataset, pipeline, sweep value) in a
// child process of its own — a crash or an out-of-memory in one method costs that run, not the sweep,
// and each run's peak memory is its own — and writes the tables. A result directory is resumable: runs
// whose metrics.json says "ok" are skipped when the same experiment is started again.
#pragma once

#include <string>
#include <vector>

#include "framework/pipeline/experiment.hpp"
#include "framework/pipeline/shard.hpp"

namespace dtsl {

struct RunnerOptions {
  std::string results_root = "results";  ///< results/<experiment>/<run_id>/
  std::string run_id;                    ///< default: default_run_id(experiment, shard)
  ShardSpec shard;                       ///< run only this part of the run list (shard.hpp)
  int jobs = 1;                          ///< runs in parallel (child processes)
  int threads = 0;                       ///< threads per run; 0: the free cores (cores.hpp) over jobs
  bool progress = true;                  ///< progress lines on stderr
  std::vector<std::string> command_line;  ///< for provenance.json
};

struct RunnerSummary {
  std::string directory;
  std::size_t total = 0, skipped = 0, succeeded = 0, failed = 0;
  std::string table_markdown;
};

/// config_hash(resolved config), with "-shard<i>of<N>" appended for a part of a sharded experiment.
std::string default_run_id(const Experiment& experiment, const ShardSpec& shard);

/// Throws ConfigError/FileError/AlgorithmError (datasets) before any run starts; then never throws for
/// a failed run (it is recorded). On an error before the first run, a directory this call created is
/// removed again.
RunnerSummary run_experiment(const Experiment& experiment, const RunnerOptions& options);

}  // namespace dtsl
