#include "framework/pipeline/shard.hpp"

#include "framework/core/error.hpp"

namespace dtsl {

std::string ShardSpec::str() const { return std::to_string(index) + "/" + std::to_string(count); }

void ShardSpec::check() const {
  if (count < 1 || count > 100000)
    throw ConfigError("--shard " + str() + ": the number of shards N must be in [1, 100000]");
  if (index < 1 || index > count)
    throw ConfigError("--shard " + str() + ": the shard index i must be in [1, N] (shards are numbered from 1)");
}

ShardSpec parse_shard(const std::string& text) {
  const auto bad = [&]() {
    return ConfigError("--shard '" + text + "': expected i/N with whole numbers 1 <= i <= N (e.g. 2/8)");
  };
  const auto slash = text.find('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 == text.size()) throw bad();
  const auto whole_number = [&](const std::string& s) {
    if (s.empty() || s.size() > 6 || s.find_first_not_of("0123456789") != std::string::npos) throw bad();
    return std::stoi(s);
  };
  ShardSpec s;
  s.index = whole_number(text.substr(0, slash));
  s.count = whole_number(text.substr(slash + 1));
  s.check();
  return s;
}

std::vector<std::size_t> shard_runs(std::size_t run_count, const ShardSpec& shard) {
  shard.check();
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < run_count; ++k)
    if (shard.contains(k)) out.push_back(k);
  return out;
}

}  // namespace dtsl
