// dtsl table DIR: regenerate the tables of a result directory from its metrics JSON.
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <iostream>

#include "experiments/cli.hpp"
#include "framework/core/error.hpp"
#include "framework/pipeline/experiment.hpp"
#include "framework/pipeline/tables.hpp"

namespace dtsl::cli {

int table_command(Args& args) {
  const std::vector<std::string> rest = args.positionals();
  if (rest.size() != 1) throw UsageError{"table: expected one result directory"};
  const std::string dir = rest[0];
  const std::string config = dir + "/config.yaml";
  if (!std::filesystem::exists(config)) throw FileError(dir, "not a result directory (no config.yaml)");
  // The column layout and the name come from the experiment's own resolved config.
  const Experiment ex = load_experiment(config, {});
  const std::string title = ex.name + " (" + std::filesystem::path(dir).filename().string() + ")";
  std::cout << write_tables(dir, ex.table_columns, title);
  return 0;
}

}  // namespace dtsl::cli
