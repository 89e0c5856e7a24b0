// Sharding an experiment: `dtsl run CONFIG --shard i/N` runs the i-th of N disjoint parts of the run
// list, so one experiment can be spread over a cluster's job array and joined again by `dtsl merge`.
// The partition is by run index: run k (0-based, in the experiment's run order) belongs to shard
// (k mod N) + 1. Shards are numbered 1..N, like Slurm's `--array=1-N` and `seq 1 N`.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace dtsl {

struct ShardSpec {
  int index = 1;  ///< 1-based, in [1, count]
  int count = 1;  ///< number of shards; 1 = the whole experiment

  bool whole() const { return count == 1; }
  /// Whether the run at 0-based position `run_index` belongs to this shard.
  bool contains(std::size_t run_index) const { return static_cast<int>(run_index % count) + 1 == index; }
  /// "i/N"
  std::string str() const;
  /// ConfigError naming the rule broken: count in [1, 100000], index in [1, count].
  void check() const;
};

/// Parses "i/N" (e.g. "2/8"). ConfigError quoting the text for anything else.
ShardSpec parse_shard(const std::string& text);

/// The 0-based run positions of `shard` among `run_count` runs, in order.
std::vector<std::size_t> shard_runs(std::size_t run_count, const ShardSpec& shard);

}  // namespace dtsl
