// libFuzzer target: the experiment loader (load_experiment: YAML syntax, keys, types, ranges, plugin
// names, sweep expansion) on arbitrary bytes, with every plugin registered as in `dtsl`. Input after
// a NUL byte is a list of "key=value" overrides (one per line), as `--set` passes them. A rejection must
// be a dtsl::Error (ConfigError / FileError naming the key or file).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "experiments/plugins.hpp"
#include "framework/core/error.hpp"
#include "framework/pipeline/experiment.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool registered = (dtsl::register_all_plugins(), true);
  (void)registered;
  static const std::string path = "/tmp/dtsl_fuzz_experiment_" + std::to_string(::getpid()) + ".yaml";
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t nul = input.find('\0');
  const std::string_view config = input.substr(0, nul);
  std::vector<std::string> overrides;
  if (nul != std::string_view::npos) {
    std::string_view rest = input.substr(nul + 1);
    while (!rest.empty()) {
      const std::size_t nl = rest.find('\n');
      overrides.emplace_back(rest.substr(0, nl));
      rest = nl == std::string_view::npos ? std::string_view() : rest.substr(nl + 1);
    }
  }
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) __builtin_trap();
  if (!config.empty() && std::fwrite(config.data(), 1, config.size(), f) != config.size()) __builtin_trap();
  std::fclose(f);
  try {
    const dtsl::Experiment ex = dtsl::load_experiment(path, overrides);
    if (ex.runs.empty()) {
      std::fprintf(stderr, "fuzz property violated: an experiment without runs was accepted\n");
      __builtin_trap();
    }
    (void)dtsl::config_hash(ex.resolved);
  } catch (const dtsl::Error&) {
  }
  std::remove(path.c_str());
  return 0;
}
