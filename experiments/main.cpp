// dtsl: the command line of the framework. `dtsl help` lists the commands.
#include <iostream>
#include <new>

#include "experiments/cli.hpp"
#include "experiments/plugins.hpp"
#include "framework/core/allocator.hpp"
#include "framework/core/error.hpp"

namespace {

const char* kUsage = R"(usage: dtsl COMMAND [ARGS]

commands:
  run CONFIG [--set KEY=VALUE ...] [--jobs N] [--results DIR] [--run-id ID] [--quiet]
             [--shard i/N] [--dry-run]
        run an experiment (datasets x pipelines x sweep values); writes
        DIR/<experiment>/<run-id>/ (default DIR: results, run-id: a hash of the config)
        with meshes, metrics JSON per run and tables (Markdown, CSV, LaTeX).
        Started again, it skips the runs that finished.
        --shard i/N: only runs k with k mod N = i-1 (i = 1..N); default run-id <hash>-shard<i>of<N>
        --dry-run: list the runs (index, id) and the result directory; write nothing
  merge OUT_DIR SHARD_DIR...
        join the result directories of an experiment's shards into OUT_DIR (new), with the
        tables an unsharded run would have; refuses different configs, overlaps, missing runs
  report RESULT_DIR [--views N] [--size PIXELS] [--up x|y|z] [--closeup F] [--no-renders] [--quiet]
        figures (renders of every run's points and stage meshes, convergence and timing plots,
        metric-versus-parameter plots of sweeps) into RESULT_DIR/figures/ and RESULT_DIR/report.md
  table RESULT_DIR
        regenerate the tables of a result directory from its metrics JSON
  reconstruct IN OUT [--pipeline NAME] [--set KEY=VALUE ...]
        reconstruct one point file (.ply .obj .off .xyz .pcd) into one mesh file (.ply .obj .off)
  list [KIND]
        every plugin (pipelines, shapes, samplers, corruptions, ...) with its options and defaults
  help  this text
)";

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> all(argv, argv + argc);
  if (argc < 2) {
    std::cerr << kUsage;
    return 2;
  }
  dtsl::configure_allocator();
  const std::string command = argv[1];
  dtsl::cli::Args args(std::vector<std::string>(argv + 2, argv + argc));
  try {
    dtsl::register_all_plugins();
    if (command == "help" || command == "--help" || command == "-h") {
      std::cout << kUsage;
      return 0;
    }
    if (command == "run") return dtsl::cli::run_command(args, all);
    if (command == "table") return dtsl::cli::table_command(args);
    if (command == "merge") return dtsl::cli::merge_command(args, all);
    if (command == "report") return dtsl::cli::report_command(args);
    if (command == "reconstruct") return dtsl::cli::reconstruct_command(args);
    if (command == "list") return dtsl::cli::list_command(args);
    throw dtsl::cli::UsageError{"unknown command '" + command + "'"};
  } catch (const dtsl::cli::UsageError& e) {
    std::cerr << "dtsl: " << e.message << "\n(see `dtsl help`)\n";
    return 2;
  } catch (const dtsl::Error& e) {
    std::cerr << "dtsl: error: " << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "dtsl: error: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "dtsl: error: " << e.what() << "\n";
    return 1;
  }
}
