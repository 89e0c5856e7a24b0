// Private to algorithms/baselines: running a command line through /bin/sh with a time limit, for the
// `external` pipeline. Linux only (fork/exec; a process group per command so a timeout kills the whole
// tree the shell started; PR_SET_PDEATHSIG so the command dies with the run that started it).
#pragma once

#include <string>

namespace dtsl::baselines {

/// How a command ended.
struct CommandOutcome {
  bool timed_out = false;   ///< killed after the time limit
  int exit_status = -1;     ///< exit code if it exited, else -1
  int signal = 0;           ///< the signal that ended it, if any (SIGKILL after a timeout)
  double seconds = 0.0;     ///< wall time
  double peak_memory_mib = 0.0;  ///< peak resident set of the shell and the children it waited for
  std::string output_tail;  ///< the end of what it wrote to stderr (else stdout), at most a few lines

  bool succeeded() const { return !timed_out && signal == 0 && exit_status == 0; }
  /// "exit status 3", "killed by signal 11 (Segmentation fault)", "timed out after 600 s".
  std::string describe() const;
};

/// Runs `command` with /bin/sh -c in the current directory, stdin from /dev/null, stdout and stderr to
/// files in `log_dir`; kills its process group after `timeout_seconds`. Throws AlgorithmError only if
/// the shell cannot be started.
CommandOutcome run_shell_command(const std::string& command, const std::string& log_dir, double timeout_seconds);

/// `text` quoted for /bin/sh: unchanged if it holds only characters the shell never interprets
/// (letters, digits, / . _ - + , : @ %), so it also works inside the user's own quotes; else in single
/// quotes.
std::string shell_quote(const std::string& text);

/// The first word of a command line (a leading quoted word is unquoted): the program it runs.
std::string command_program(const std::string& command);

/// Whether `program` can be executed: a path (with a '/') names an executable regular file; a bare
/// name is looked up in $PATH, and shell builtins are not recognised.
bool program_available(const std::string& program);

}  // namespace dtsl::baselines
