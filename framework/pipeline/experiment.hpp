// An experiment: datasets x pipelines (x sweep values), read from YAML. Parsing validates everything
// (unknown keys, plugin names, option types and ranges, dataset specs) before any output is written.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <string>
#include <vector>

#include "framework/config/options.hpp"
#include "framework/datasets/dataset.hpp"

namespace dtsl {

/// Options of the ground-truth comparison (docs/design.md §5).
struct MetricsOptions final : Options {
  int samples = 100000;            ///< area-uniform samples on result and ground truth each
  double fscore_tau_ratio = 0.005;  ///< F-score threshold as a fraction of the truth's bbox diagonal
  bool stage_surfaces = false;      ///< compare every stage's mesh with the truth too, not only the result

  void visit(FieldVisitor& v) override;
  void check() const override;
};

/// One sweep axis: a YAML path and the values it takes. Several axes form their Cartesian product.
struct SweepAxis {
  std::string key;
  std::vector<YAML::Node> values;
};

/// One unit of work: a dataset and a pipeline, fully resolved (sweep values applied).
struct RunSpec {
  std::string id;            ///< unique, file-name safe: "<dataset>__<pipeline>[__<key>=<value>...]"
  std::string dataset_name;  ///< as in the config
  std::string dataset_key;   ///< cache key: the dataset name plus the sweep values that change it
  std::string pipeline_name;
  std::string pipeline_type;
  YAML::Node dataset;        ///< the resolved dataset entry
  YAML::Node pipeline;       ///< the resolved pipeline entry
  std::vector<std::pair<std::string, std::string>> sweep;  ///< (key, value) that apply to this run
};

struct Experiment {
  std::string name;
  std::string description;
  std::uint64_t seed = 1;
  double timeout_seconds = 0.0;  ///< per run; 0 = none
  MetricsOptions metrics;
  FilesFrame files_frame = FilesFrame::input;  ///< `files_frame:` input (default) or normalised
  std::vector<std::string> table_columns;  ///< empty: the default columns
  YAML::Node resolved;                     ///< the whole config with --set overrides applied
  std::vector<SweepAxis> sweep;
  std::vector<RunSpec> runs;
};

/// Reads and validates `path` with "key=value" overrides applied. ConfigError / FileError naming the
/// file and key on any problem. Plugins must be registered (register_all_plugins()).
Experiment load_experiment(const std::string& path, const std::vector<std::string>& overrides);

/// The same from an already-loaded document; `origin` names it in messages.
Experiment parse_experiment(YAML::Node root, const std::string& origin);

/// A short stable hash of the resolved config (the default run id of its result directory).
std::string config_hash(const YAML::Node& resolved);

}  // namespace dtsl
