#include "algorithms/baselines/shell_command.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"

extern char** environ;

namespace dtsl::baselines {

std::string CommandOutcome::describe() const {
  std::ostringstream s;
  if (timed_out)
    s << "timed out after " << seconds << " s";
  else if (signal != 0)
    s << "killed by signal " << signal << " (" << strsignal(signal) << ")";
  else
    s << "exit status " << exit_status;
  return s.str();
}

namespace {

// The last `max_lines` lines of `path` (at most `max_chars` characters), without trailing blank lines.
std::string file_tail(const std::string& path, std::size_t max_lines = 12, std::size_t max_chars = 1500) {
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  std::size_t start = text.size();
  for (std::size_t lines = 0; lines < max_lines && start > 0; ++lines) {
    const std::size_t newline = text.rfind('\n', start - 1);
    start = newline == std::string::npos ? 0 : newline;
  }
  if (start < text.size() && text[start] == '\n') ++start;
  if (text.size() - start > max_chars) start = text.size() - max_chars;
  return text.substr(start);
}

}  // namespace

CommandOutcome run_shell_command(const std::string& command, const std::string& log_dir, double timeout_seconds) {
  const std::string out_path = log_dir + "/stdout.txt", err_path = log_dir + "/stderr.txt";
  // Everything the child needs is prepared before fork: between fork and exec only async-signal-safe
  // calls (the parent may run OpenMP threads).
  const int out_fd = open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  const int err_fd = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  const int null_fd = open("/dev/null", O_RDONLY | O_CLOEXEC);
  auto close_all = [&] {
    for (int fd : {out_fd, err_fd, null_fd})
      if (fd >= 0) close(fd);
  };
  if (out_fd < 0 || err_fd < 0 || null_fd < 0) {
    close_all();
    throw AlgorithmError("cannot open the log files of '" + command + "' in " + log_dir);
  }
  std::string shell = "/bin/sh", dash_c = "-c", body = command;
  char* argv[] = {shell.data(), dash_c.data(), body.data(), nullptr};
  const pid_t parent = getpid();
  Stopwatch clock;
  const pid_t pid = fork();
  if (pid == 0) {
    // A process group of its own, so a timeout kills the shell and everything it started; and it dies
    // with this process (a run the sweep kills must not leave the command running).
    setpgid(0, 0);
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(126);
    if (dup2(null_fd, 0) < 0 || dup2(out_fd, 1) < 0 || dup2(err_fd, 2) < 0) _exit(126);
    execve("/bin/sh", argv, environ);
    _exit(127);
  }
  const int fork_error = errno;
  close_all();
  if (pid < 0) throw AlgorithmError("cannot start /bin/sh for '" + command + "': " + std::strerror(fork_error));
  setpgid(pid, pid);  // also from this side, so the group exists before any kill below

  CommandOutcome outcome;
  int status = 0;
  rusage usage{};
  auto wait_for = [&](int flags) {
    pid_t r;
    do r = wait4(pid, &status, flags, &usage);
    while (r < 0 && errno == EINTR);
    return r;
  };
  // Polling keeps this free of signal handlers (the runner and OpenMP own the process's signals).
  std::chrono::milliseconds pause(1);
  pid_t waited;
  while ((waited = wait_for(WNOHANG)) == 0) {
    if (clock.seconds() > timeout_seconds) {
      kill(-pid, SIGKILL);
      wait_for(0);
      outcome.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::milliseconds(50));
  }
  const int wait_error = errno;
  kill(-pid, SIGKILL);  // anything the shell left behind in its group
  if (waited < 0)
    throw AlgorithmError("cannot wait for '" + command + "': " + std::strerror(wait_error));
  outcome.seconds = clock.seconds();
  outcome.peak_memory_mib = static_cast<double>(usage.ru_maxrss) / 1024.0;  // KiB on Linux
  if (!outcome.timed_out) {
    if (WIFEXITED(status)) outcome.exit_status = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) outcome.signal = WTERMSIG(status);
  } else {
    outcome.signal = SIGKILL;
  }
  outcome.output_tail = file_tail(err_path);
  if (outcome.output_tail.empty()) outcome.output_tail = file_tail(out_path);
  return outcome;
}

std::string shell_quote(const std::string& text) {
  const bool plain = !text.empty() && std::all_of(text.begin(), text.end(), [](unsigned char c) {
    return std::isalnum(c) || std::strchr("/._-+,:@%", c) != nullptr;
  });
  if (plain) return text;
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string command_program(const std::string& command) {
  std::size_t i = command.find_first_not_of(" \t\n");
  if (i == std::string::npos) return "";
  const char quote = command[i];
  if (quote == '\'' || quote == '"') {
    const std::size_t end = command.find(quote, i + 1);
    return command.substr(i + 1, end == std::string::npos ? std::string::npos : end - i - 1);
  }
  const std::size_t end = command.find_first_of(" \t\n;&|<>()", i);
  return command.substr(i, end == std::string::npos ? std::string::npos : end - i);
}

bool program_available(const std::string& program) {
  auto executable = [](const std::string& path) {
    struct stat st{};
    return stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && access(path.c_str(), X_OK) == 0;
  };
  if (program.empty()) return false;
  if (program.find('/') != std::string::npos) return executable(program);
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "/usr/local/bin:/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');)
    if (executable((dir.empty() ? "." : dir) + "/" + program)) return true;
  return false;
}

}  // namespace dtsl::baselines
