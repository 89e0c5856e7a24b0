#include "framework/pipeline/merge.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "framework/core/atomic_file.hpp"
#include "framework/core/error.hpp"
#include "framework/pipeline/experiment.hpp"
#include "framework/pipeline/provenance.hpp"
#include "framework/pipeline/tables.hpp"

namespace dtsl {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw FileError(p.string(), "cannot read");
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

json read_json(const fs::path& p) {
  std::ifstream in(p);
  if (!in) throw FileError(p.string(), "cannot read");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw FileError(p.string(), std::string("malformed JSON: ") + e.what());
  }
}

/// Hard-links every file of `from` into `to` (made here), copying where links are impossible.
void link_tree(const fs::path& from, const fs::path& to) {
  fs::create_directories(to);
  for (const auto& entry : fs::recursive_directory_iterator(from)) {
    const fs::path target = to / fs::relative(entry.path(), from);
    if (entry.is_directory()) {
      fs::create_directories(target);
    } else if (entry.is_regular_file() && entry.path().filename().string().find(".tmp-") == std::string::npos) {
      // (a *.tmp-<pid> file is what a killed writer left: not part of the result)
      std::error_code ec;
      fs::create_hard_link(entry.path(), target, ec);
      if (ec) fs::copy_file(entry.path(), target);
    }
  }
}

struct Shard {
  fs::path dir;
  json provenance;                      // empty object if the file is missing
  std::map<std::string, fs::path> runs;  // run id -> its folder (with a metrics.json)
};

}  // namespace

MergeSummary merge_results(const std::string& out_dir, const std::vector<std::string>& shard_dirs,
                           const std::vector<std::string>& command_line) {
  if (shard_dirs.empty()) throw ConfigError("merge: no shard directories given");
  const fs::path out = fs::path(out_dir).lexically_normal();
  if (out.filename().empty()) throw ConfigError("merge: '" + out_dir + "' is not a directory name");
  if (fs::exists(out)) throw FileError(out_dir, "already exists; merge writes a new result directory");

  // 1. Every shard is a result directory of the same config.
  std::vector<Shard> shards;
  std::string config_text;
  std::set<fs::path> seen_dirs;
  for (const std::string& d : shard_dirs) {
    Shard s;
    s.dir = fs::path(d);
    if (!fs::is_regular_file(s.dir / "config.yaml") || !fs::is_directory(s.dir / "runs"))
      throw FileError(d, "not a result directory (needs config.yaml and runs/)");
    if (!seen_dirs.insert(fs::weakly_canonical(s.dir)).second) throw ConfigError("merge: '" + d + "' given twice");
    const std::string text = read_text(s.dir / "config.yaml");
    if (shards.empty()) config_text = text;
    else if (text != config_text)
      throw ConfigError("merge: '" + d + "' holds a different configuration (config.yaml) than '" +
                        shards.front().dir.string() + "'; only shards of one experiment can be merged");
    s.provenance = fs::exists(s.dir / "provenance.json") ? read_json(s.dir / "provenance.json") : json::object();
    shards.push_back(std::move(s));
  }
  const Experiment ex = load_experiment((shards.front().dir / "config.yaml").string(), {});
  const std::string hash = config_hash(ex.resolved);
  for (const Shard& s : shards)
    if (s.provenance.contains("config_hash") && s.provenance["config_hash"] != hash)
      throw ConfigError("merge: '" + s.dir.string() + "': provenance.json names config " +
                        s.provenance["config_hash"].dump() + ", its config.yaml hashes to " + hash);

  // 2. Shard bookkeeping, where recorded, is consistent: one N, each index once.
  std::map<int, fs::path> indices;
  int count = 0;
  for (const Shard& s : shards) {
    if (!s.provenance.contains("shard")) continue;
    const int i = s.provenance["shard"].value("index", 0), n = s.provenance["shard"].value("count", 0);
    if (count && n != count)
      throw ConfigError("merge: '" + s.dir.string() + "' is shard " + std::to_string(i) + "/" + std::to_string(n) +
                        " but another is of " + std::to_string(count) + " shards");
    count = n;
    if (indices.count(i))
      throw ConfigError("merge: '" + s.dir.string() + "' and '" + indices[i].string() + "' are both shard " +
                        std::to_string(i) + "/" + std::to_string(n));
    indices[i] = s.dir;
  }

  // 3. Runs: each run of the experiment exactly once, nothing else.
  std::set<std::string> known;
  for (const RunSpec& r : ex.runs) known.insert(r.id);
  std::map<std::string, const Shard*> owner;
  for (Shard& s : shards) {
    for (const auto& entry : fs::directory_iterator(s.dir / "runs")) {
      if (!entry.is_directory()) continue;
      const std::string id = entry.path().filename().string();
      if (!fs::exists(entry.path() / "metrics.json")) continue;  // started, never finished: not a result
      if (!known.count(id))
        throw ConfigError("merge: '" + s.dir.string() + "' has run '" + id + "', which is not a run of experiment '" +
                          ex.name + "'");
      if (owner.count(id))
        throw ConfigError("merge: run '" + id + "' is in both '" + owner[id]->dir.string() + "' and '" +
                          s.dir.string() + "'; shards must not overlap");
      owner[id] = &s;
      s.runs[id] = entry.path();
    }
  }
  std::vector<std::string> missing;
  for (const RunSpec& r : ex.runs)
    if (!owner.count(r.id)) missing.push_back(r.id);
  if (!missing.empty()) {
    std::string list;
    for (std::size_t i = 0; i < missing.size() && i < 5; ++i) list += (i ? ", " : "") + missing[i];
    if (missing.size() > 5) list += ", ...";
    throw ConfigError("merge: " + std::to_string(missing.size()) + " of " + std::to_string(ex.runs.size()) +
                      " runs of experiment '" + ex.name + "' are in none of the directories (" + list +
                      "); run the missing shards first");
  }

  // 4. Build next to the target, then rename into place.
  const fs::path tmp = out.parent_path() / (out.filename().string() + ".tmp-merge-" + std::to_string(::getpid()));
  MergeSummary summary;
  try {
    fs::remove_all(tmp);
    fs::create_directories(tmp / "runs");
    fs::create_directories(tmp / "datasets");
    for (const Shard& s : shards) {
      for (const auto& [id, path] : s.runs) link_tree(path, tmp / "runs" / id);
      if (fs::is_directory(s.dir / "datasets"))
        for (const auto& entry : fs::directory_iterator(s.dir / "datasets"))
          if (entry.is_directory() && !fs::exists(tmp / "datasets" / entry.path().filename()))
            link_tree(entry.path(), tmp / "datasets" / entry.path().filename());
    }
    write_file_atomically((tmp / "config.yaml").string(), [&](std::ostream& o) { o << config_text; });
    json prov = provenance(command_line);
    prov["seed"] = ex.seed;
    prov["run_id"] = out.filename().string();
    prov["config_hash"] = hash;
    json from = json::array();
    for (const Shard& s : shards) from.push_back({{"directory", s.dir.string()}, {"provenance", s.provenance}});
    prov["merged_from"] = from;
    write_file_atomically((tmp / "provenance.json").string(), [&](std::ostream& o) { o << prov.dump(2) << "\n"; });
    summary.table_markdown = write_tables(tmp.string(), ex.table_columns, ex.name + " (" + out.filename().string() + ")");
    for (const json& r : load_run_records(tmp.string())) {
      ++summary.runs;
      if (r.value("status", std::string()) != "ok") ++summary.failed;
    }
    if (!out.parent_path().empty()) fs::create_directories(out.parent_path());
    fs::rename(tmp, out);
  } catch (...) {
    std::error_code ec;
    fs::remove_all(tmp, ec);
    throw;
  }
  return summary;
}

}  // namespace dtsl
