// Shared pieces of the dtsl command line: argument walking and the commands' entry points.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace dtsl::cli {

/// A usage error: exit code 2 with the message and a pointer to `dtsl help`.
struct UsageError {
  std::string message;
};

/// Walks argv; options may come before or after positional arguments.
class Args {
 public:
  Args(std::vector<std::string> args) : args_(std::move(args)) {}
  /// The value after `--name` (or `--name=value`); all occurrences are consumed by values().
  bool flag(const std::string& name);
  std::string value(const std::string& name, const std::string& fallback = "");
  std::vector<std::string> values(const std::string& name);
  /// Remaining arguments; a leftover --option is a UsageError naming the closest known option.
  std::vector<std::string> positionals();
  /// A count given as text: a UsageError naming `--name` unless it is an integer in [min, max].
  static int integer(const std::string& name, const std::string& text, int min, int max);

 private:
  std::vector<std::string> args_;
  std::vector<std::string> known_;  ///< the options asked for so far, for "did you mean"
};

/// `dtsl help`: the commands with a line each.
void print_overview(std::ostream& out);
/// `dtsl COMMAND --help`: usage, options and an example; false for an unknown command.
bool print_command_help(const std::string& command, std::ostream& out);
std::vector<std::string> command_names();
/// `dtsl --version`: version, git commit, library versions.
void print_version(std::ostream& out);

int run_command(Args& args, const std::vector<std::string>& command_line);
int table_command(Args& args);
int merge_command(Args& args, const std::vector<std::string>& command_line);
int report_command(Args& args);
int reconstruct_command(Args& args);
int list_command(Args& args);

}  // namespace dtsl::cli
