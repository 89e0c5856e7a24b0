// `dtsl merge OUT SHARD...`: joins the result directories of the shards of one experiment (runner.hpp,
// shard.hpp) into one result directory, laid out and tabled exactly as an unsharded run would be.
#pragma once

#include <string>
#include <vector>

namespace dtsl {

struct MergeSummary {
  std::size_t runs = 0;     ///< runs in the merged directory (= the experiment's run count)
  std::size_t failed = 0;   ///< of which the record says not "ok"
  std::string table_markdown;
};

/// Checks, before writing anything, that every directory is a result directory of the same resolved
/// config (config.yaml, and config_hash in provenance.json where present), that no run is in two of
/// them and that together they hold a finished record (metrics.json) of every run of the experiment;
/// throws ConfigError / FileError naming the directory and the run otherwise. Then builds `out_dir`
/// (which must not exist) next to itself and renames it into place, so a failure leaves nothing:
/// run folders and datasets are hard-linked (copied across file systems), config.yaml copied,
/// provenance.json records the shards' provenance, and the tables are written from the records.
/// Plugins must be registered (the config is validated again).
MergeSummary merge_results(const std::string& out_dir, const std::vector<std::string>& shard_dirs,
                           const std::vector<std::string>& command_line);

}  // namespace dtsl
