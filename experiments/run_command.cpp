// dtsl run CONFIG: see framework/pipeline/runner.hpp.
#include <unistd.h>

#include <iostream>

#include "experiments/cli.hpp"
#include "framework/core/error.hpp"
#include "framework/pipeline/experiment.hpp"
#include "framework/pipeline/runner.hpp"
#include "framework/pipeline/shard.hpp"

namespace dtsl::cli {

int run_command(Args& args, const std::vector<std::string>& command_line) {
  RunnerOptions options;
  std::vector<std::string> overrides = args.values("set");
  // The same switch as reconstruct's: the experiment's files in the [-1,1]^3 frame.
  if (args.flag("normalised")) overrides.push_back("files_frame=normalised");
  const std::string jobs = args.value("jobs", "1");
  const std::string threads = args.value("threads");
  options.results_root = args.value("results", "results");
  options.run_id = args.value("run-id");
  options.progress = !args.flag("quiet");
  const std::string shard = args.value("shard");
  const bool dry_run = args.flag("dry-run");
  options.command_line = command_line;
  const std::vector<std::string> rest = args.positionals();
  if (rest.size() != 1) throw UsageError{"run: expected one CONFIG file"};
  try {
    std::size_t used = 0;
    options.jobs = std::stoi(jobs, &used);
    if (used != jobs.size()) throw std::invalid_argument(jobs);
  } catch (const std::exception&) {
    throw UsageError{"--jobs: expected a number, got '" + jobs + "'"};
  }
  if (!threads.empty()) options.threads = Args::integer("threads", threads, 1, 1024);
  if (!options.run_id.empty() &&
      options.run_id.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") !=
          std::string::npos)
    throw UsageError{"--run-id: use letters, digits, '_', '-', '.'"};

  if (!shard.empty()) {
    try {
      options.shard = parse_shard(shard);
    } catch (const ConfigError& e) {
      throw UsageError{e.what()};
    }
  }

  const Experiment ex = load_experiment(rest[0], overrides);
  if (dry_run) {  // what would run, and where; nothing is written
    const std::string run_id = options.run_id.empty() ? default_run_id(ex, options.shard) : options.run_id;
    const std::vector<std::size_t> mine = shard_runs(ex.runs.size(), options.shard);
    std::cout << "# " << ex.name << (options.shard.whole() ? "" : " shard " + options.shard.str()) << ": "
              << mine.size() << " of " << ex.runs.size() << " runs -> " << options.results_root << "/" << ex.name
              << "/" << run_id << "\n";
    for (const std::size_t i : mine) std::cout << i << "\t" << ex.runs[i].id << "\n";
    return 0;
  }
  const RunnerSummary s = run_experiment(ex, options);
  std::cout << s.table_markdown << "\n";
  std::cerr << ex.name << ": " << s.succeeded << " ran, " << s.skipped << " already done, " << s.failed
            << " failed; results in " << s.directory << "\n";
  return s.failed == 0 ? 0 : 1;
}

}  // namespace dtsl::cli
