#include "framework/pipeline/experiment.hpp"

#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include "framework/config/yaml_options.hpp"
#include "framework/config/yaml_path.hpp"
#include "framework/core/error.hpp"
#include "framework/core/suggest.hpp"
#include "framework/datasets/dataset.hpp"
#include "framework/pipeline/preset.hpp"
#include "framework/pipeline/reconstructor.hpp"
#include "framework/pipeline/tables.hpp"

namespace dtsl {

void MetricsOptions::visit(FieldVisitor& v) {
  v.field("samples", samples, "area-uniform samples on result and ground truth, each (docs/design.md §5)");
  v.field("fscore_tau_ratio", fscore_tau_ratio, "F-score threshold as a fraction of the truth's bbox diagonal");
  v.field("stage_surfaces", stage_surfaces,
          "also compare every stage's mesh (MI, MD, MS) with the ground truth: which phase gains or loses "
          "accuracy (columns chamfer@MI, accuracy@MD, ...); one surface comparison per stage");
}

void MetricsOptions::check() const {
  check_range("samples", samples, 100, 100000000);
  check_range("fscore_tau_ratio", fscore_tau_ratio, 1e-6, 1.0);
}

namespace {

const std::set<std::string> kTopLevelKeys = {"experiment", "description", "seed",  "timeout_seconds", "metrics",
                                             "files_frame", "datasets",   "pipelines",   "sweep", "table"};

bool valid_name(const std::string& s) {
  if (s.empty() || s.size() > 80) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) return false;
  return s != "." && s != "..";
}

std::string safe(const std::string& s) {
  std::string out;
  for (char c : s) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_') ? c : '_';
  return out;
}

std::string scalar(const YAML::Node& n, const std::string& key) {
  if (!n.IsScalar()) throw ConfigError(key + ": expected a string");
  return n.Scalar();
}

std::string dump(const YAML::Node& n) {
  YAML::Emitter e;
  e << n;
  return e.c_str();
}

void check_keys(const YAML::Node& map, const std::set<std::string>& allowed, const std::string& context) {
  for (auto it = map.begin(); it != map.end(); ++it) {
    if (!it->first.IsScalar())
      throw ConfigError((context.empty() ? std::string("the top level") : context) + ": a key is a " +
                        (it->first.IsSequence() ? "list" : it->first.IsMap() ? "map" : "null") + ", not a name");
    const std::string k = it->first.Scalar();
    if (!allowed.count(k)) {
      std::string known;
      for (const auto& a : allowed) known += (known.empty() ? "" : ", ") + a;
      throw ConfigError((context.empty() ? k : context + "." + k) + ": unknown key" +
                        did_you_mean(k, std::vector<std::string>(allowed.begin(), allowed.end())) + "; known keys: " + known);
    }
  }
}

/// Validates a pipeline entry {name, type, preset, options}; returns its label.
std::string validate_pipeline(const YAML::Node& p, const std::string& context) {
  if (!p.IsMap())
    throw ConfigError(context + ": expected a map with 'type' (and optional 'name', 'preset', 'options')");
  check_keys(p, {"name", "type", "preset", "options"}, context);
  if (!p["type"]) throw ConfigError(context + ".type: missing (one of the registered pipelines; see `dtsl list`)");
  const std::string type = scalar(p["type"], context + ".type");
  const std::string name = p["name"] ? scalar(p["name"], context + ".name") : type;
  if (!valid_name(name)) throw ConfigError(context + ".name: '" + name + "' must be letters, digits, '_', '-', '.'");
  auto plugin = reconstructors().create(type, context + ".type");
  if (p["preset"]) apply_preset(*plugin, type, scalar(p["preset"], context + ".preset"), context + ".preset");
  apply_yaml(plugin->options(), p["options"], context + ".options");
  return name;
}

std::string validate_dataset(const YAML::Node& d, const std::string& context) {
  DatasetSpec spec = parse_dataset(d, context);
  if (!valid_name(spec.name))
    throw ConfigError(context + ".name: '" + spec.name + "' must be letters, digits, '_', '-', '.'");
  return spec.name;
}

}  // namespace

Experiment load_experiment(const std::string& path, const std::vector<std::string>& overrides) {
  std::ifstream in(path);
  if (!in) throw FileError(path, "cannot open experiment file");
  YAML::Node root;
  try {
    root = YAML::Load(in);
  } catch (const YAML::ParserException& e) {
    throw FileError(path, "YAML syntax error: " + e.msg, e.mark.line >= 0 ? e.mark.line + 1 : -1);
  }
  if (!root.IsMap()) throw FileError(path, "expected a YAML map with keys experiment, datasets, pipelines");
  for (const std::string& o : overrides) {
    auto [key, value] = split_assignment(o);
    YAML::Node parsed;
    try {
      parsed = YAML::Load(value);
    } catch (const YAML::Exception&) {
      throw ConfigError("--set " + key + ": cannot parse value '" + value + "'");
    }
    if (!parsed.IsDefined() || parsed.IsNull()) parsed = YAML::Node(value);
    try {
      set_yaml_path(root, key, parsed);
    } catch (const ConfigError& e) {
      throw ConfigError(std::string("--set ") + e.what());
    }
  }
  try {
    return parse_experiment(root, path);
  } catch (const ConfigError& e) {
    throw ConfigError(path + ": " + e.what());
  } catch (const YAML::Exception& e) {
    // A structure no check above foresaw: still name the file, and the place yaml-cpp reports.
    throw ConfigError(path + ": unexpected structure: " + e.what());
  }
}

Experiment parse_experiment(YAML::Node root, const std::string& origin) {
  (void)origin;
  Experiment ex;
  check_keys(root, kTopLevelKeys, "");
  if (!root["experiment"]) throw ConfigError("experiment: missing (the experiment's name)");
  ex.name = scalar(root["experiment"], "experiment");
  if (!valid_name(ex.name)) throw ConfigError("experiment: '" + ex.name + "' must be letters, digits, '_', '-', '.'");
  if (root["description"]) ex.description = scalar(root["description"], "description");
  if (root["seed"]) {
    try {
      const long long s = root["seed"].as<long long>();
      if (s < 0) throw ConfigError("seed: must not be negative");
      ex.seed = static_cast<std::uint64_t>(s);
    } catch (const YAML::Exception&) {
      throw ConfigError("seed: expected a non-negative integer, got '" + dump(root["seed"]) + "'");
    }
  }
  if (root["timeout_seconds"]) {
    try {
      ex.timeout_seconds = root["timeout_seconds"].as<double>();
    } catch (const YAML::Exception&) {
      throw ConfigError("timeout_seconds: expected a number");
    }
    if (!(ex.timeout_seconds >= 0)) throw ConfigError("timeout_seconds: must not be negative");
  }
  apply_yaml(ex.metrics, root["metrics"], "metrics");
  if (root["files_frame"]) {
    const std::string frame = scalar(root["files_frame"], "files_frame");
    if (frame != "input" && frame != "normalised")
      throw ConfigError("files_frame: must be 'input' (meshes and points in the input's units) or 'normalised' "
                        "(the [-1,1]^3 frame the errors are measured in), got '" + frame + "'");
    ex.files_frame = frame == "input" ? FilesFrame::input : FilesFrame::normalised;
  }
  if (root["table"]) {
    const YAML::Node t = root["table"];
    if (!t.IsMap()) throw ConfigError("table: expected a map with 'columns'");
    check_keys(t, {"columns"}, "table");
    if (t["columns"]) {
      if (!t["columns"].IsSequence()) throw ConfigError("table.columns: expected a list of column names");
      for (std::size_t i = 0; i < t["columns"].size(); ++i)
        ex.table_columns.push_back(scalar(t["columns"][i], "table.columns[" + std::to_string(i) + "]"));
      check_columns(ex.table_columns);
    }
  }

  const YAML::Node datasets = root["datasets"], pipelines = root["pipelines"];
  if (!datasets || !datasets.IsSequence() || datasets.size() == 0)
    throw ConfigError("datasets: expected a non-empty list of datasets");
  if (!pipelines || !pipelines.IsSequence() || pipelines.size() == 0)
    throw ConfigError("pipelines: expected a non-empty list of pipelines");
  std::set<std::string> seen;
  for (std::size_t i = 0; i < datasets.size(); ++i) {
    const std::string n = validate_dataset(datasets[i], "datasets[" + std::to_string(i) + "]");
    if (!seen.insert("d:" + n).second) throw ConfigError("datasets[" + std::to_string(i) + "].name: '" + n + "' used twice");
  }
  for (std::size_t i = 0; i < pipelines.size(); ++i) {
    const std::string n = validate_pipeline(pipelines[i], "pipelines[" + std::to_string(i) + "]");
    if (!seen.insert("p:" + n).second) throw ConfigError("pipelines[" + std::to_string(i) + "].name: '" + n + "' used twice");
  }

  if (root["sweep"]) {
    YAML::Node s = root["sweep"];
    if (s.IsMap()) {  // a single axis may be written without the list
      YAML::Node list(YAML::NodeType::Sequence);
      list.push_back(s);
      s.reset(list);  // reset, not =: assignment would write into the config document itself
    }
    if (!s.IsSequence()) throw ConfigError("sweep: expected {key, values} or a list of them");
    for (std::size_t i = 0; i < s.size(); ++i) {
      const std::string ctx = "sweep[" + std::to_string(i) + "]";
      if (!s[i].IsMap()) throw ConfigError(ctx + ": expected {key, values}");
      check_keys(s[i], {"key", "values"}, ctx);
      if (!s[i]["key"]) throw ConfigError(ctx + ".key: missing");
      if (!s[i]["values"] || !s[i]["values"].IsSequence() || s[i]["values"].size() == 0)
        throw ConfigError(ctx + ".values: expected a non-empty list");
      SweepAxis axis{scalar(s[i]["key"], ctx + ".key"), {}};
      for (std::size_t k = 0; k < s[i]["values"].size(); ++k) axis.values.push_back(s[i]["values"][k]);
      ex.sweep.push_back(axis);
    }
  }
  // A hostile or mistaken sweep (ten axes of ten values) would make the expansion below run for hours.
  constexpr std::size_t kMaxCombinations = 1000;
  std::size_t combinations = 1;
  for (const SweepAxis& axis : ex.sweep) {
    combinations *= axis.values.size();  // each factor is >= 1 and the product stays below the limit
    if (combinations > kMaxCombinations)
      throw ConfigError("sweep: more than " + std::to_string(kMaxCombinations) +
                        " combinations of values; split the experiment");
  }
  ex.resolved = root;

  // Expand the sweep's Cartesian product; a run names only the sweep axes that address its dataset or
  // its pipeline, so pipelines a sweep does not touch run once, not once per value. What an axis
  // addresses is found by writing a probe value at its path (comparing with the swept values would miss
  // a value equal to the config's own).
  std::vector<std::vector<bool>> axis_dataset(ex.sweep.size()), axis_pipeline(ex.sweep.size());
  for (std::size_t a = 0; a < ex.sweep.size(); ++a) {
    YAML::Node probe = YAML::Clone(root);
    try {
      set_yaml_path(probe, ex.sweep[a].key, YAML::Node("__dtsl_sweep_probe__"));
    } catch (const ConfigError& e) {
      throw ConfigError("sweep[" + std::to_string(a) + "].key: " + e.what());
    }
    for (const char* list : {"datasets", "pipelines"})
      if (!probe[list].IsSequence() || probe[list].size() != root[list].size())
        throw ConfigError("sweep[" + std::to_string(a) + "].key: '" + ex.sweep[a].key + "' replaces the " + list +
                          " list; sweep one of their keys");
    for (std::size_t di = 0; di < root["datasets"].size(); ++di)
      axis_dataset[a].push_back(dump(probe["datasets"][di]) != dump(root["datasets"][di]));
    for (std::size_t pi = 0; pi < root["pipelines"].size(); ++pi)
      axis_pipeline[a].push_back(dump(probe["pipelines"][pi]) != dump(root["pipelines"][pi]));
  }
  std::vector<std::size_t> index(ex.sweep.size(), 0);
  std::set<std::string> ids;
  for (;;) {
    YAML::Node doc = YAML::Clone(root);
    std::vector<std::pair<std::string, std::string>> assignment;
    for (std::size_t a = 0; a < ex.sweep.size(); ++a) {
      const YAML::Node& v = ex.sweep[a].values[index[a]];
      set_yaml_path(doc, ex.sweep[a].key, YAML::Clone(v));
      assignment.push_back({ex.sweep[a].key, v.IsScalar() ? v.Scalar() : dump(v)});
    }
    for (std::size_t di = 0; di < doc["datasets"].size(); ++di) {
      const YAML::Node d = doc["datasets"][di];
      const std::string dctx = "datasets[" + std::to_string(di) + "]";
      const std::string dname = validate_dataset(d, dctx);
      std::vector<std::pair<std::string, std::string>> dsweep;
      for (std::size_t a = 0; a < assignment.size(); ++a)
        if (axis_dataset[a][di]) dsweep.push_back(assignment[a]);
      for (std::size_t pi = 0; pi < doc["pipelines"].size(); ++pi) {
        const YAML::Node p = doc["pipelines"][pi];
        RunSpec run;
        run.dataset_name = dname;
        run.pipeline_name = validate_pipeline(p, "pipelines[" + std::to_string(pi) + "]");
        run.pipeline_type = p["type"].Scalar();
        run.dataset = YAML::Clone(d);
        run.pipeline = YAML::Clone(p);
        run.sweep = dsweep;
        for (std::size_t a = 0; a < assignment.size(); ++a)
          if (axis_pipeline[a][pi]) run.sweep.push_back(assignment[a]);
        run.dataset_key = dname;
        for (const auto& [k, v] : dsweep) run.dataset_key += "__" + safe(k + "=" + v);
        run.id = dname + "__" + run.pipeline_name;
        for (const auto& [k, v] : run.sweep) run.id += "__" + safe(k + "=" + v);
        if (ids.insert(run.id).second) ex.runs.push_back(std::move(run));
      }
    }
    std::size_t a = 0;
    for (; a < index.size(); ++a) {
      if (++index[a] < ex.sweep[a].values.size()) break;
      index[a] = 0;
    }
    if (a == index.size()) break;
  }
  return ex;
}

std::string config_hash(const YAML::Node& resolved) {
  const std::string text = dump(resolved);
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a: stable across platforms, unlike std::hash
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return std::string(buf, 8);
}

}  // namespace dtsl
