// dtsl merge OUT_DIR SHARD_DIR...: see framework/pipeline/merge.hpp.
#include <iostream>

#include "experiments/cli.hpp"
#include "framework/pipeline/merge.hpp"

namespace dtsl::cli {

int merge_command(Args& args, const std::vector<std::string>& command_line) {
  const std::vector<std::string> rest = args.positionals();
  if (rest.size() < 2) throw UsageError{"merge: expected OUT_DIR and at least one SHARD_DIR"};
  const std::vector<std::string> shards(rest.begin() + 1, rest.end());
  const MergeSummary s = merge_results(rest[0], shards, command_line);
  std::cout << s.table_markdown << "\n";
  std::cerr << "merged " << shards.size() << " directories: " << s.runs << " runs (" << s.failed
            << " not ok) in " << rest[0] << "\n";
  return 0;
}

}  // namespace dtsl::cli
