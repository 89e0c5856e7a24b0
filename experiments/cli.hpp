// Shared pieces of the dtsl command line: argument walking and the commands' entry points.
#pragma once

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
  /// Remaining arguments; a leftover --option is a UsageError.
  std::vector<std::string> positionals();

 private:
  std::vector<std::string> args_;
};

int run_command(Args& args, const std::vector<std::string>& command_line);
int table_command(Args& args);
int merge_command(Args& args, const std::vector<std::string>& command_line);
int report_command(Args& args);
int reconstruct_command(Args& args);
int list_command(Args& args);

}  // namespace dtsl::cli
