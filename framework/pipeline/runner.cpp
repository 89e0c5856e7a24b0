#include "framework/pipeline/runner.hpp"

#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <thread>


#include "framework/core/atomic_file.hpp"
#include "framework/core/cores.hpp"
#include "framework/core/error.hpp"
#include "framework/pipeline/dataset_cache.hpp"
#include "framework/pipeline/provenance.hpp"
#include "framework/pipeline/run_one.hpp"
#include "framework/pipeline/tables.hpp"

namespace dtsl {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

std::string dump_yaml(const YAML::Node& n) {
  YAML::Emitter e;
  e << n;
  return std::string(e.c_str()) + "\n";
}

bool run_finished(const std::string& run_dir) {
  std::ifstream in(run_dir + "/metrics.json");
  if (!in) return false;
  try {
    return json::parse(in).value("status", std::string()) == "ok";
  } catch (const json::exception&) {
    return false;  // unreadable: run it again
  }
}

void write_record(const std::string& run_dir, const json& record) {
  fs::create_directories(run_dir);
  write_file_atomically(run_dir + "/metrics.json", [&](std::ostream& o) { o << record.dump(2) << "\n"; });
}

/// Interrupts (Ctrl-C) stop the parent's loop; the children are killed and nothing finished is lost.
volatile sig_atomic_t g_interrupted = 0;
void on_signal(int) { g_interrupted = 1; }

struct Child {
  pid_t pid;
  std::size_t index;
  std::chrono::steady_clock::time_point started;
};

void prepare_datasets(const Experiment& ex, const std::vector<std::size_t>& runs, const std::string& dir,
                      bool progress) {
  std::set<std::string> done;
  for (const std::size_t index : runs) {
    const RunSpec& run = ex.runs[index];
    if (!done.insert(run.dataset_key).second) continue;
    const std::string ddir = dir + "/datasets/" + run.dataset_key;
    if (dataset_complete(ddir, ex.files_frame)) continue;
    if (progress) std::cerr << "dataset " << run.dataset_key << " ..." << std::flush;
    DatasetSpec spec = parse_dataset(run.dataset, run.dataset_key);
    const Dataset d = build_dataset(spec, ex.seed);
    write_dataset(ddir, d, ex.files_frame);
    if (progress) std::cerr << " " << d.points.size() << " points\n";
  }
}

}  // namespace

std::string default_run_id(const Experiment& ex, const ShardSpec& shard) {
  std::string id = config_hash(ex.resolved);
  if (!shard.whole()) id += "-shard" + std::to_string(shard.index) + "of" + std::to_string(shard.count);
  return id;
}

RunnerSummary run_experiment(const Experiment& ex, const RunnerOptions& options) {
  if (options.jobs < 1 || options.jobs > 256) throw ConfigError("--jobs: must be in [1, 256]");
  const std::vector<std::size_t> mine = shard_runs(ex.runs.size(), options.shard);
  RunnerSummary summary;
  const std::string run_id = options.run_id.empty() ? default_run_id(ex, options.shard) : options.run_id;
  const std::string dir = options.results_root + "/" + ex.name + "/" + run_id;
  summary.directory = dir;
  summary.total = mine.size();
  const std::string config_text = dump_yaml(ex.resolved);

  const bool existed = fs::exists(dir), root_existed = fs::exists(options.results_root);
  if (existed) {
    std::ifstream in(dir + "/config.yaml");
    std::string previous((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in || previous != config_text)
      throw ConfigError(dir + ": holds the results of a different configuration; choose another --run-id");
    // Nor may one directory mix shards (merge tells shards apart by their provenance).
    std::ifstream pin(dir + "/provenance.json");
    json prev;
    try {
      if (pin) prev = json::parse(pin);
    } catch (const json::exception&) {
    }
    const std::string was = prev.contains("shard") ? std::to_string(prev["shard"].value("index", 0)) + "/" +
                                                         std::to_string(prev["shard"].value("count", 0))
                                                   : "1/1";
    if (pin && was != options.shard.str())
      throw ConfigError(dir + ": holds " + (was == "1/1" ? std::string("the unsharded run") : "shard " + was) +
                        " of this experiment, not " + (options.shard.whole() ? std::string("the unsharded run") : "shard " + options.shard.str()) +
                        "; choose another --run-id");
    remove_stale_temporaries(dir);  // what a killed sweep was writing: its runs are redone below
  }
  try {
    fs::create_directories(dir + "/runs");
    write_file_atomically(dir + "/config.yaml", [&](std::ostream& o) { o << config_text; });
    json prov = provenance(options.command_line);
    prov["seed"] = ex.seed;
    prov["run_id"] = run_id;
    prov["config_hash"] = config_hash(ex.resolved);
    if (!options.shard.whole()) {
      json ids = json::array();
      for (const std::size_t i : mine) ids.push_back(ex.runs[i].id);
      prov["shard"] = {{"index", options.shard.index}, {"count", options.shard.count}, {"runs", ids}};
    }
    write_file_atomically(dir + "/provenance.json", [&](std::ostream& o) { o << prov.dump(2) << "\n"; });
    prepare_datasets(ex, mine, dir, options.progress);
  } catch (...) {
    if (!existed) {
      std::error_code ec;
      fs::remove_all(dir, ec);
      // Remove the experiment folder and the results root too if this call made them and they are now
      // empty (fs::remove leaves a non-empty folder alone).
      fs::remove(fs::path(dir).parent_path(), ec);
      if (!root_existed) fs::remove(options.results_root, ec);
    }
    throw;
  }

  std::vector<std::size_t> todo;
  for (const std::size_t i : mine) {
    if (run_finished(dir + "/runs/" + ex.runs[i].id)) ++summary.skipped;
    else todo.push_back(i);
  }
  if (options.progress)
    std::cerr << ex.name << (options.shard.whole() ? "" : " shard " + options.shard.str()) << ": " << mine.size()
              << " runs, " << summary.skipped << " already done, writing to "
              << dir << "\n";

  struct sigaction sa{}, old_int{}, old_term{};
  sa.sa_handler = on_signal;
  sigaction(SIGINT, &sa, &old_int);
  sigaction(SIGTERM, &sa, &old_term);
  g_interrupted = 0;

  std::map<pid_t, Child> running;
  std::size_t next = 0, finished = 0;
  const int threads_per_run = std::max(1, free_cores() / std::max(1, options.jobs));
  // A parent with threads (an OpenMP pool from earlier work in this process, an embedding program's
  // own) forks children that may use OpenMP with one thread only (process_threads(), cores.hpp).
  const bool parent_has_threads = process_threads() > 1;
  if (parent_has_threads && options.progress && !todo.empty())
    std::cerr << "each run uses one thread: this process already has threads (earlier parallel work, or an "
                 "embedding program's own); `dtsl run` in a fresh process uses the free cores\n";
  auto finish = [&](const Child& c, const json& record) {
    ++finished;
    const RunSpec& run = ex.runs[c.index];
    const bool ok = record.value("status", std::string()) == "ok";
    ok ? ++summary.succeeded : ++summary.failed;
    if (options.progress) {
      const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - c.started).count();
      std::fprintf(stderr, "[%zu/%zu] %s: %s (%.1f s)%s%s\n", finished, todo.size(), run.id.c_str(),
                   ok ? "ok" : record.value("status", std::string("failed")).c_str(), secs, ok ? "" : " — ",
                   ok ? "" : record.value("error", std::string()).c_str());
    }
  };

  while ((next < todo.size() || !running.empty()) && !g_interrupted) {
    while (next < todo.size() && running.size() < static_cast<std::size_t>(options.jobs)) {
      const std::size_t index = todo[next++];
      const RunSpec& run = ex.runs[index];
      const std::string run_dir = dir + "/runs/" + run.id;
      std::fflush(nullptr);
      const pid_t parent = ::getpid();
      const pid_t pid = ::fork();
      if (pid < 0) throw Error("cannot start a run: fork failed");
      if (pid == 0) {
        // A run dies with the sweep (even one killed by SIGKILL): an orphan would go on writing into a
        // run folder that the sweep, started again, redoes at the same time.
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (::getppid() != parent) ::_exit(3);  // the sweep died before prctl
        ::signal(SIGINT, SIG_DFL);
        ::signal(SIGTERM, SIG_DFL);
        // N runs side by side share the free cores: more threads than free cores make OpenMP's threads
        // wait on each other at every barrier (a run 2-6x slower). A parent with threads allows one
        // (above); else OMP_NUM_THREADS, when set, decides unless `threads` is given.
        if (parent_has_threads) set_threads(1);
        else if (options.threads > 0) set_threads(options.threads);
        else if (!std::getenv("OMP_NUM_THREADS")) set_threads(threads_per_run);
        // The libraries' own chatter (PCL prints to stdout/stderr) goes to the run's log, not the terminal.
        std::error_code ec;
        fs::create_directories(run_dir, ec);
        if (FILE* log = std::fopen((run_dir + "/log.txt").c_str(), "w")) {
          ::dup2(fileno(log), STDOUT_FILENO);
          ::dup2(fileno(log), STDERR_FILENO);
          std::fclose(log);
        }
        if (parent_has_threads)
          std::fprintf(stderr, "one thread: the process that started this run has threads of its own "
                               "(process_threads(), cores.hpp)\n");
        int code = 0;
        try {
          const Dataset d = read_dataset(dir + "/datasets/" + run.dataset_key);
          json record = execute_run(run, d, ex.metrics, ex.seed, run_dir, ex.files_frame);
          record["order"] = index;
          write_record(run_dir, record);
        } catch (const std::exception& e) {
          std::fprintf(stderr, "%s: %s\n", run.id.c_str(), e.what());
          code = 3;
        }
        std::fflush(nullptr);
        ::_exit(code);
      }
      running[pid] = Child{pid, index, std::chrono::steady_clock::now()};
    }
    int status = 0;
    rusage usage{};
    const pid_t done = ::wait4(-1, &status, WNOHANG, &usage);
    if (done > 0 && running.count(done)) {
      const Child c = running[done];
      running.erase(done);
      const RunSpec& run = ex.runs[c.index];
      const std::string run_dir = dir + "/runs/" + run.id;
      json record;
      std::ifstream in(run_dir + "/metrics.json");
      bool have = false;
      if (in && WIFEXITED(status) && WEXITSTATUS(status) == 0) {
        try {
          record = json::parse(in);
          have = true;
        } catch (const json::exception&) {
        }
      }
      if (!have) {
        record = {{"run", run.id}, {"dataset", run.dataset_name}, {"pipeline", run.pipeline_name},
                  {"type", run.pipeline_type}, {"order", c.index}, {"status", "failed"}};
        record["sweep"] = json::object();
        for (const auto& [k, v] : run.sweep) record["sweep"][k] = v;
        record["error"] = WIFSIGNALED(status) ? "crashed with signal " + std::to_string(WTERMSIG(status)) +
                                                    (WTERMSIG(status) == SIGKILL ? " (killed: out of memory or timeout)" : "")
                                              : "exited with code " + std::to_string(WEXITSTATUS(status));
        write_record(run_dir, record);
      }
      finish(c, record);
      continue;
    }
    // Enforce the per-run time limit.
    if (ex.timeout_seconds > 0)
      for (auto& [pid, c] : running)
        if (std::chrono::duration<double>(std::chrono::steady_clock::now() - c.started).count() > ex.timeout_seconds) {
          ::kill(pid, SIGKILL);
          ::waitpid(pid, &status, 0);
          const RunSpec& run = ex.runs[c.index];
          json record = {{"run", run.id}, {"dataset", run.dataset_name}, {"pipeline", run.pipeline_name},
                         {"type", run.pipeline_type}, {"order", c.index}, {"status", "timeout"},
                         {"error", "exceeded timeout_seconds = " + std::to_string(ex.timeout_seconds)}};
          record["sweep"] = json::object();
          for (const auto& [k, v] : run.sweep) record["sweep"][k] = v;
          write_record(dir + "/runs/" + run.id, record);
          const Child copy = c;
          running.erase(pid);
          finish(copy, record);
          break;
        }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (g_interrupted) {
    for (auto& [pid, c] : running) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
    sigaction(SIGINT, &old_int, nullptr);
    sigaction(SIGTERM, &old_term, nullptr);
    throw Error("interrupted: " + std::to_string(summary.succeeded + summary.skipped) + " of " +
                std::to_string(summary.total) + " runs are finished in " + dir + "; run the same command again to resume");
  }
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);

  summary.table_markdown = write_tables(dir, ex.table_columns, ex.name + " (" + run_id + ")");
  return summary;
}

}  // namespace dtsl
