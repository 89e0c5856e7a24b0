// Running the dtsl command line as a child process with a time limit, for the robustness tests: its
// exit code or the signal that ended it, its output (stdout and stderr together), and whether it had
// to be killed for running too long. Also: a scratch folder, and the corpus' expectations file.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace dtsl::test {

struct Outcome {
  int exit_code = -1;  ///< when the process exited normally
  int signal = 0;      ///< when a signal ended it (a crash, or our SIGKILL at the time limit)
  bool timed_out = false;
  std::string output;

  bool crashed() const { return signal != 0 && !timed_out; }
  std::string describe() const {
    if (timed_out) return "hung (killed at the time limit)";
    if (signal) return "crashed with signal " + std::to_string(signal);
    return "exit code " + std::to_string(exit_code);
  }
};

/// Seconds a single command may take: $DTSL_ROBUSTNESS_TIMEOUT, else `fallback` (sanitizer builds are
/// several times slower, so CI may raise it).
inline double command_timeout(double fallback) {
  const char* e = std::getenv("DTSL_ROBUSTNESS_TIMEOUT");
  return e && *e ? std::atof(e) : fallback;
}

/// Runs `args` (args[0]: the program) in a process group of its own, with `env` entries ("K=V") added
/// to the environment; kills the whole group with SIGKILL after `timeout` seconds.
inline Outcome run_process(const std::vector<std::string>& args, double timeout,
                           const std::vector<std::string>& env = {}) {
  char pattern[] = "/tmp/dtsl-robustness-out-XXXXXX";
  const int out_fd = ::mkstemp(pattern);
  REQUIRE(out_fd >= 0);
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    ::setpgid(0, 0);
    ::dup2(out_fd, STDOUT_FILENO);
    ::dup2(out_fd, STDERR_FILENO);
    const int null_fd = ::open("/dev/null", O_RDONLY);
    if (null_fd >= 0) ::dup2(null_fd, STDIN_FILENO);
    for (const std::string& e : env) ::putenv(const_cast<char*>(e.c_str()));
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::setpgid(pid, pid);  // also here: no race with the child's own call
  Outcome o;
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  for (;;) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > timeout) {
      ::kill(-pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      o.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(-pid, SIGKILL);  // anything the command left running in its group
  if (WIFEXITED(status)) o.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) o.signal = WTERMSIG(status);
  ::lseek(out_fd, 0, SEEK_SET);
  char buf[4096];
  for (ssize_t n; (n = ::read(out_fd, buf, sizeof buf)) > 0;) o.output.append(buf, static_cast<std::size_t>(n));
  ::close(out_fd);
  ::unlink(pattern);
  return o;
}

/// A fresh folder under /tmp, removed with everything in it when the object goes.
class ScratchDir {
 public:
  ScratchDir() {
    char pattern[] = "/tmp/dtsl-robustness-XXXXXX";
    REQUIRE(::mkdtemp(pattern) != nullptr);
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  /// Every file under the folder, as paths relative to it.
  std::vector<std::string> files() const {
    std::vector<std::string> out;
    for (const auto& e : std::filesystem::recursive_directory_iterator(path_))
      if (!e.is_directory()) out.push_back(std::filesystem::relative(e.path(), path_).string());
    return out;
  }

 private:
  std::filesystem::path path_;
};

inline bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

/// One line of corpus/expectations.txt: "<file> | <error|either> | <substring>".
struct CorpusEntry {
  std::string file;  ///< relative to the corpus folder
  bool must_fail = true;
  std::string expected;
};

inline std::string trimmed(std::string s) {
  const auto b = s.find_first_not_of(" \t");
  const auto e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

inline std::vector<CorpusEntry> read_expectations(const std::string& path) {
  std::ifstream in(path);
  REQUIRE(in);
  std::vector<CorpusEntry> out;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    const auto a = line.find('|'), b = line.find('|', a + 1);
    REQUIRE(b != std::string::npos);
    const std::string outcome = trimmed(line.substr(a + 1, b - a - 1));
    REQUIRE((outcome == "error" || outcome == "either"));
    out.push_back({trimmed(line.substr(0, a)), outcome == "error", trimmed(line.substr(b + 1))});
  }
  return out;
}

}  // namespace dtsl::test
