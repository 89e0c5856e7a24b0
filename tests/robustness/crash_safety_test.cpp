// Crash safety: a sweep killed with SIGKILL in the middle (after at least one run finished) and started
// again loses no finished run, recomputes none, leaves no temporary file and ends with complete tables.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "tests/robustness/process.hpp"

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace dtsl::test;

namespace {

// Six short runs (Poisson at six depths), one at a time.
const char* kSweep = R"(experiment: killed
seed: 5
metrics: {samples: 1000}
datasets:
  - {name: ball, shape: sphere, sampler: {type: area, count: 1500}}
pipelines:
  - {name: poisson, type: pcl_poisson, options: {depth: 5}}
sweep:
  - {key: pipelines.poisson.options.depth, values: [5, 6, 7, 8, 9, 10]}
)";

std::string text_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

bool finished_ok(const fs::path& metrics) {
  if (!fs::exists(metrics)) return false;
  try {
    return json::parse(text_of(metrics)).value("status", "") == "ok";
  } catch (const json::exception&) {
    return false;
  }
}

}  // namespace

TEST_CASE("a sweep killed with SIGKILL resumes without losing or redoing finished runs", "[.crash]") {
  ScratchDir dir;
  const std::string config = (dir.path() / "killed.yaml").string();
  std::ofstream(config) << kSweep;
  const fs::path results = dir.path() / "results";
  const fs::path runs = results / "killed" / "r" / "runs";
  const std::vector<std::string> command = {DTSL_EXECUTABLE, "run", config, "--results", results.string(),
                                            "--run-id", "r", "--quiet"};

  // Start the sweep; once a run is finished and another is under way, kill the sweep process itself.
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    const int null_fd = ::open("/dev/null", O_WRONLY);
    ::dup2(null_fd, STDOUT_FILENO);
    ::dup2(null_fd, STDERR_FILENO);
    std::vector<char*> argv;
    for (const std::string& a : command) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  const auto count_finished = [&] {
    std::size_t n = 0;
    if (fs::exists(runs))
      for (const auto& e : fs::directory_iterator(runs)) n += finished_ok(e.path() / "metrics.json");
    return n;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(command_timeout(600));
  bool exited = false;
  while (count_finished() < 1 && std::chrono::steady_clock::now() < deadline) {
    if (::waitpid(pid, nullptr, WNOHANG) == pid) {
      exited = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  REQUIRE_FALSE(exited);  // the sweep must still be running when the first run is done
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  REQUIRE(WIFSIGNALED(status));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // let a run orphaned by the kill die

  // What was finished at the kill, with the time its record was written.
  std::map<std::string, fs::file_time_type> finished;
  for (const auto& e : fs::directory_iterator(runs))
    if (finished_ok(e.path() / "metrics.json"))
      finished[e.path().filename().string()] = fs::last_write_time(e.path() / "metrics.json");
  REQUIRE(!finished.empty());
  REQUIRE(finished.size() < 6);  // killed mid-sweep, not after it

  const Outcome again = run_process(command, command_timeout(600));
  INFO(again.describe() << "\n" << again.output);
  REQUIRE(again.exit_code == 0);

  // Nothing finished was redone or lost; every run has a parsable, successful record.
  for (const auto& [run, stamp] : finished) {
    INFO(run);
    CHECK(fs::last_write_time(runs / run / "metrics.json") == stamp);
  }
  std::size_t records = 0;
  for (const auto& e : fs::directory_iterator(runs)) {
    INFO(e.path());
    const json record = json::parse(text_of(e.path() / "metrics.json"));
    CHECK(record.value("status", "") == "ok");
    CHECK(fs::exists(e.path() / "final.ply"));
    ++records;
  }
  CHECK(records == 6);

  // No temporary file anywhere; the tables list every run.
  for (const auto& e : fs::recursive_directory_iterator(results)) {
    INFO(e.path());
    CHECK(e.path().filename().string().find(".tmp-") == std::string::npos);
  }
  const std::string csv = text_of(results / "killed" / "r" / "table.csv");
  std::size_t rows = 0;
  for (char ch : csv) rows += ch == '\n';
  CHECK(rows == 1 + 6);  // a header and one row per run
  for (const char* f : {"table.md", "table.tex"}) CHECK(fs::exists(results / "killed" / "r" / f));
}
