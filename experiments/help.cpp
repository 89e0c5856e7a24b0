// The command line's own documentation: `dtsl help`, `dtsl COMMAND --help`, `dtsl --version`.
#include <iostream>

#include "experiments/cli.hpp"
#include "framework/core/suggest.hpp"
#include "framework/pipeline/provenance.hpp"

namespace dtsl::cli {

namespace {

struct CommandHelp {
  const char* name;
  const char* summary;
  const char* text;  ///< usage, options, an example
};

const CommandHelp kCommands[] = {
    {"reconstruct", "reconstruct one point file into one mesh file",
     R"(usage: dtsl reconstruct IN OUT [options]

Reconstructs the points of IN (.ply .obj .off .xyz .pcd) into the mesh OUT (.ply .obj .off), in
IN's own units. Everything that can be checked is checked before the reconstruction starts: IN
readable with enough points, OUT's folder writable and its extension known, the --set keys.

options:
  --pipeline NAME     the reconstructor (default dtsl; `dtsl list pipeline` shows all)
  --preset NAME       the pipeline's option values to start from (default: default; dtsl also has
                      paper, the method as published; `dtsl list preset` shows them)
  --set KEY=VALUE     a pipeline option over the preset (repeatable; `dtsl list pipeline NAME`)
  --stages DIR        also write every stage's mesh into DIR (stage_MI.ply, ...)
  --metrics FILE      write timings, counts and errors as JSON (with --truth: against the truth)
  --truth MESH        a ground-truth mesh in IN's units, measured against in --metrics
  --normalised        write OUT and the stage meshes in the [-1,1]^3 frame the method works in
  --threads N         threads (default: the cores not busy right now)
  --quiet             no progress on stderr

example:
  dtsl reconstruct scan.xyz scan.ply --stages scan_stages --metrics scan.json
)"},
    {"run", "run an experiment (datasets x pipelines x sweep values)",
     R"(usage: dtsl run CONFIG [options]

Runs an experiment: every dataset through every pipeline and sweep value, each run in a child process.
Writes DIR/<experiment>/<run-id>/ with the datasets, each run's meshes and metrics JSON, and the tables
(Markdown, CSV, LaTeX). Started again, it skips the runs that finished.

options:
  --set KEY=VALUE     override a config value (repeatable), e.g. --set seed=2
  --jobs N            runs side by side (default 1)
  --threads N         threads per run (default: the cores not busy right now, over --jobs)
  --results DIR       the results root (default results)
  --run-id ID         the result folder's name (default: a hash of the resolved config)
  --shard i/N         only runs k with k mod N = i-1 (a Slurm array task; `dtsl merge` joins them)
  --normalised        write points, truths and meshes in the [-1,1]^3 frame the errors are measured in
                      (the config's files_frame: normalised); default: in the input's units
  --dry-run           list the runs and the result directory; write nothing
  --quiet             no progress on stderr

example:
  dtsl run configs/quick.yaml --jobs 2 --run-id reference
)"},
    {"report", "figures and report.md of a result directory",
     R"(usage: dtsl report RESULT_DIR [options]

Renders every run's points and stage meshes, convergence and timing plots and the metric-versus-
parameter plots of sweeps into RESULT_DIR/figures/, and writes RESULT_DIR/report.md.

options:
  --views N           views per mesh (default 2)
  --size PIXELS       side of a panel (default 360)
  --up x|y|z          the up axis of the views (default y)
  --closeup F         zoom of the close-up views (default 1: none)
  --no-renders        plots only
  --quiet             no progress on stderr

example:
  dtsl report results/quick/reference
)"},
    {"table", "regenerate the tables of a result directory",
     R"(usage: dtsl table RESULT_DIR

Writes the tables (Markdown, CSV, LaTeX) of RESULT_DIR again from its metrics JSON and prints the
Markdown one.

example:
  dtsl table results/quick/reference
)"},
    {"merge", "join the result directories of an experiment's shards",
     R"(usage: dtsl merge OUT_DIR SHARD_DIR...

Joins the result directories of `dtsl run --shard i/N` into OUT_DIR (new), with the tables an
unsharded run would have; refuses different configs, overlaps and missing runs.

example:
  dtsl merge results/suite/all results/suite/*-shard*
)"},
    {"list", "the plugins and their options",
     R"(usage: dtsl list [KIND [NAME]]

Without arguments: every kind of plugin with its names. With KIND (pipeline, shape, sampler,
corruption, polygonizer, ...): each plugin of that kind with a line of what it does. With KIND NAME:
that plugin's options, their types, defaults and meaning. `dtsl list columns` lists the table columns.

example:
  dtsl list pipeline dtsl
)"},
    {"help", "this overview, or a command's help", R"(usage: dtsl help [COMMAND]
)"},
};

}  // namespace

void print_overview(std::ostream& out) {
  out << "usage: dtsl COMMAND [ARGS]   (dtsl COMMAND --help for a command's options)\n\ncommands:\n";
  for (const CommandHelp& c : kCommands) {
    const std::string name = c.name;
    out << "  " << name << std::string(name.size() < 13 ? 13 - name.size() : 1, ' ') << c.summary << "\n";
  }
  out << "\n  --version    version, git commit and library versions\n";
}

bool print_command_help(const std::string& command, std::ostream& out) {
  for (const CommandHelp& c : kCommands)
    if (command == c.name) {
      out << c.text;
      return true;
    }
  return false;
}

std::vector<std::string> command_names() {
  std::vector<std::string> names;
  for (const CommandHelp& c : kCommands) names.push_back(c.name);
  return names;
}

void print_version(std::ostream& out) {
  const nlohmann::json p = provenance({});
  const std::string commit = p.value("git_commit", std::string());
  out << "dtsl " << DTSL_VERSION << "\n"
      << "git commit: " << (commit.empty() ? "unknown (not a git checkout)" : commit)
      << (p.value("git_dirty", false) ? " (with uncommitted changes)" : "") << "\n"
      << "libraries: " << p.value("libraries", std::string()) << "\n";
  if (p.contains("compiler")) out << "compiler: " << p["compiler"].get<std::string>() << "\n";
}

}  // namespace dtsl::cli
