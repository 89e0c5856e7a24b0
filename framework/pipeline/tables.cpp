#include "framework/pipeline/tables.hpp"
#include "framework/pipeline/json_lookup.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>

#include "framework/core/atomic_file.hpp"
#include "framework/core/error.hpp"
#include "framework/core/suggest.hpp"

namespace dtsl {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

constexpr auto at = json_at;

constexpr auto number = format_json_number;

const json* stage_with(const json& r, const char* key, const std::string& value) {
  if (!r.contains("stages")) return nullptr;
  for (const json& s : r["stages"])
    if (s.value(key, std::string()) == value) return &s;
  return nullptr;
}

/// "1" if the result has the truth's genus and components (so it is closed, as a genus is only defined
/// for a closed mesh), "0" if not, "–" without a result or without a closed truth to compare with.
std::string topology_ok(const json& r) {
  const json *tg = at(r, {"truth_mesh", "genus"}), *tc = at(r, {"truth_mesh", "components"});
  const json* mesh = at(r, {"final", "mesh"});
  if (!tg || !tg->is_number() || !tc || !tc->is_number() || !mesh) return "–";
  const json *g = at(*mesh, {"genus"}), *c = at(*mesh, {"components"});
  const bool same = g && g->is_number() && c && c->is_number() && g->get<double>() == tg->get<double>() &&
                    c->get<double>() == tc->get<double>();
  return same ? "1" : "0";
}

struct ColumnDef {
  std::string header;
  std::function<std::string(const json&)> cell;
};

/// The columns without an "@": name -> definition.
const std::map<std::string, ColumnDef>& fixed_columns() {
  static const std::map<std::string, ColumnDef> fixed = {
      {"dataset", {"dataset", [](const json& r) { return r.value("dataset", std::string()); }}},
      {"pipeline", {"pipeline", [](const json& r) { return r.value("pipeline", std::string()); }}},
      {"type", {"type", [](const json& r) { return r.value("type", std::string()); }}},
      {"np", {"np", [](const json& r) { return number(at(r, {"np"}), 1, "%.0f"); }}},
      {"nv", {"nv", [](const json& r) { return number(at(r, {"final", "mesh", "vertices"}), 1, "%.0f"); }}},
      {"nf", {"nf", [](const json& r) { return number(at(r, {"final", "mesh", "faces"}), 1, "%.0f"); }}},
      {"e_avr", {"e_avr (1e-3)", [](const json& r) { return number(at(r, {"final", "point_errors", "e_avr"}), 1e3, "%.2f"); }}},
      {"e_max", {"e_max (1e-3)", [](const json& r) { return number(at(r, {"final", "point_errors", "e_max"}), 1e3, "%.2f"); }}},
      {"accuracy", {"acc (1e-3)", [](const json& r) { return number(at(r, {"final", "surface", "accuracy"}), 1e3, "%.2f"); }}},
      {"completeness", {"comp (1e-3)", [](const json& r) { return number(at(r, {"final", "surface", "completeness"}), 1e3, "%.2f"); }}},
      {"chamfer", {"chamfer (1e-3)", [](const json& r) { return number(at(r, {"final", "surface", "chamfer"}), 1e3, "%.2f"); }}},
      {"hausdorff", {"hausdorff (1e-3)", [](const json& r) { return number(at(r, {"final", "surface", "hausdorff"}), 1e3, "%.1f"); }}},
      {"nc", {"normal cons.", [](const json& r) { return number(at(r, {"final", "surface", "normal_consistency"}), 1, "%.3f"); }}},
      {"fscore", {"F-score", [](const json& r) { return number(at(r, {"final", "surface", "fscore"}), 1, "%.3f"); }}},
      {"watertight", {"watertight", [](const json& r) {
                        const json* v = at(r, {"final", "mesh", "watertight"});
                        return v && v->is_boolean() ? (v->get<bool>() ? "yes" : "no") : "–";
                      }}},
      {"components", {"comp.", [](const json& r) { return number(at(r, {"final", "mesh", "components"}), 1, "%.0f"); }}},
      {"genus", {"genus", [](const json& r) { return number(at(r, {"final", "mesh", "genus"}), 1, "%.0f"); }}},
      {"truth_components", {"truth comp.", [](const json& r) { return number(at(r, {"truth_mesh", "components"}), 1, "%.0f"); }}},
      {"truth_genus", {"truth genus", [](const json& r) { return number(at(r, {"truth_mesh", "genus"}), 1, "%.0f"); }}},
      {"topology_ok", {"topology ok", topology_ok}},
      {"min_angle", {"min angle p1 (deg)", [](const json& r) { return number(at(r, {"final", "mesh", "min_angle_p01_deg"}), 1, "%.1f"); }}},
      {"valence6", {"valence 6", [](const json& r) { return number(at(r, {"final", "mesh", "valence6_fraction"}), 1, "%.2f"); }}},
      {"time", {"time (s)", [](const json& r) { return number(at(r, {"time_total"}), 1, "%.2f"); }}},
      {"memory", {"peak MiB", [](const json& r) { return number(at(r, {"peak_memory_mib"}), 1, "%.0f"); }}},
      {"normals", {"normals", [](const json& r) {
                     const json* v = at(r, {"summary", "normals_source"});
                     return v && v->is_string() ? v->get<std::string>() : std::string("–");
                   }}},
      {"status", {"status", [](const json& r) {
                    std::string s = r.value("status", std::string("?"));
                    if (s != "ok") {
                      std::string e = r.value("error", std::string());
                      if (e.size() > 90) e = e.substr(0, 87) + "...";
                      s += ": " + e;
                    }
                    return s;
                  }}},
  };
  return fixed;
}

/// A column name -> its definition; "name@X" forms are resolved against stages.
bool resolve(const std::string& name, ColumnDef& out) {
  const auto atpos = name.find('@');
  if (atpos != std::string::npos) {
    const std::string base = name.substr(0, atpos), label = name.substr(atpos + 1);
    if (label.empty()) return false;
    // A stage mesh's measure (point errors always; distances to the truth with metrics.stage_surfaces);
    // "final" is the result's.
    const auto stage_measure = [&out, &label](const std::string& head, const char* group, const std::string& key) {
      out = {head + " " + label + " (1e-3)", [group, key, label](const json& r) {
               const json* s = stage_with(r, "mesh_label", label);
               if (!s && label == "final") return number(at(r, {"final", group, key.c_str()}), 1e3, "%.2f");
               return s ? number(at(*s, {"measures", group, key.c_str()}), 1e3, "%.2f") : std::string("–");
             }};
      return true;
    };
    if (base == "e_avr" || base == "e_max") return stage_measure(base, "point_errors", base);
    if (base == "chamfer") return stage_measure("chamfer", "surface", base);
    if (base == "accuracy") return stage_measure("acc", "surface", base);
    if (base == "completeness") return stage_measure("comp", "surface", base);
    if (base == "nv") {
      out = {"nv " + label, [label](const json& r) {
               const json* s = stage_with(r, "mesh_label", label);
               return s ? number(at(*s, {"measures", "mesh", "vertices"}), 1, "%.0f") : std::string("–");
             }};
      return true;
    }
    if (base == "time") {
      out = {label + " (s)", [label](const json& r) {
               const json* s = stage_with(r, "name", label);
               return s ? number(at(*s, {"seconds"}), 1, "%.2f") : std::string("–");
             }};
      return true;
    }
    if (base == "stage") {  // stage@STAGE.KEY[.KEY...]: a value of a stage's summary, e.g. stage@B-Evl.iterations
      const auto dot = label.find('.');
      if (dot == std::string::npos || dot == 0 || dot + 1 == label.size() || label.back() == '.' ||
          label.find("..") != std::string::npos)
        return false;
      const std::string stage = label.substr(0, dot);
      std::vector<std::string> path;  // nested keys: stage@B-Evl.degenerate_removal.collapsed
      for (std::size_t begin = dot + 1; begin <= label.size();) {
        const std::size_t end = std::min(label.find('.', begin), label.size());
        path.push_back(label.substr(begin, end - begin));
        begin = end + 1;
      }
      out = {stage + " " + label.substr(dot + 1), [stage, path](const json& r) {
               const json* v = stage_with(r, "name", stage);
               v = v && v->contains("summary") ? &(*v)["summary"] : nullptr;
               for (const std::string& key : path) v = v && v->is_object() && v->contains(key) ? &(*v)[key] : nullptr;
               if (!v) return std::string("–");
               if (v->is_string()) return v->get<std::string>();
               return v->is_number_float() ? number(v, 1, "%.4g") : v->dump();
             }};
      return true;
    }
    if (base == "summary") {
      out = {label, [label](const json& r) {
               const json* v = at(r, {"summary"});
               if (!v || !v->contains(label)) return std::string("–");
               const json& x = (*v)[label];
               return x.is_string() ? x.get<std::string>() : x.dump();
             }};
      return true;
    }
    return false;
  }
  const std::map<std::string, ColumnDef>& fixed = fixed_columns();
  auto it = fixed.find(name);
  if (it == fixed.end()) return false;
  out = it->second;
  return true;
}

std::string escape(const std::string& s, const std::string& specials, const std::string& prefix) {
  std::string out;
  for (char c : s) {
    if (specials.find(c) != std::string::npos) out += prefix;
    out += c;
  }
  return out;
}

}  // namespace

std::vector<std::string> default_columns() {
  return {"dataset", "pipeline", "np",    "nv",         "e_avr",      "e_max", "chamfer", "hausdorff",
          "nc",      "fscore",   "watertight", "components", "genus", "time",    "memory",    "normals", "status"};
}

std::string describe_columns() {
  std::string names;
  for (const auto& [name, def] : fixed_columns()) names += name + " ";
  return names +
         "and per stage: "
         "e_avr@LABEL e_max@LABEL nv@LABEL (stage mesh label, e.g. MI MD MS), chamfer@LABEL accuracy@LABEL "
         "completeness@LABEL (with metrics.stage_surfaces), time@STAGE, stage@STAGE.KEY (a value of the stage's "
         "summary, nested keys joined by '.', e.g. stage@B-Evl.iterations), summary@KEY";
}

void check_columns(const std::vector<std::string>& columns) {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    ColumnDef d;
    if (!resolve(columns[i], d)) {
      std::vector<std::string> known;
      for (const auto& [name, def] : fixed_columns()) known.push_back(name);
      throw ConfigError("table.columns[" + std::to_string(i) + "]: unknown column '" + columns[i] + "'" +
                        did_you_mean(columns[i], known) + "; known: " + describe_columns());
    }
  }
}

Table make_table(const std::vector<json>& records, const std::vector<std::string>& columns_in) {
  std::vector<std::string> columns = columns_in.empty() ? default_columns() : columns_in;
  check_columns(columns);
  // Sweep keys present in any record become columns right after "pipeline" (or first).
  std::vector<std::string> sweep_keys;
  for (const json& r : records)
    if (r.contains("sweep"))
      for (auto it = r["sweep"].begin(); it != r["sweep"].end(); ++it)
        if (std::find(sweep_keys.begin(), sweep_keys.end(), it.key()) == sweep_keys.end()) sweep_keys.push_back(it.key());
  std::vector<ColumnDef> defs;
  for (const std::string& c : columns) {
    ColumnDef d;
    resolve(c, d);
    defs.push_back(d);
    if (c == "pipeline")
      for (const std::string& k : sweep_keys)
        defs.push_back({k.substr(k.find_last_of('.') + 1), [k](const json& r) {
                          const json* v = at(r, {"sweep"});
                          return v && v->contains(k) ? (*v)[k].get<std::string>() : std::string("–");
                        }});
  }
  Table t;
  for (const ColumnDef& d : defs) t.headers.push_back(d.header);
  for (const json& r : records) {
    std::vector<std::string> row;
    for (const ColumnDef& d : defs) row.push_back(d.cell(r));
    t.rows.push_back(row);
  }
  return t;
}

std::string to_markdown(const Table& t) {
  auto line = [](const std::vector<std::string>& cells) {
    std::string s = "|";
    for (const std::string& c : cells) s += " " + escape(c, "|", "\\") + " |";
    return s + "\n";
  };
  std::string out = line(t.headers) + "|";
  for (std::size_t i = 0; i < t.headers.size(); ++i) out += i < 2 ? " --- |" : " ---: |";
  out += "\n";
  for (const auto& r : t.rows) out += line(r);
  return out;
}

std::string to_csv(const Table& t) {
  auto line = [](const std::vector<std::string>& cells) {
    std::string s;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      std::string c = cells[i] == "–" ? "" : cells[i];
      if (c.find_first_of(",\"\n") != std::string::npos) c = "\"" + escape(c, "\"", "\"") + "\"";
      s += (i ? "," : "") + c;
    }
    return s + "\n";
  };
  std::string out = line(t.headers);
  for (const auto& r : t.rows) out += line(r);
  return out;
}

std::string to_latex(const Table& t, const std::string& caption) {
  auto tex = [](const std::string& s) { return escape(s, "_%&#$", "\\"); };
  std::string out = "\\begin{table}\n\\centering\n\\begin{tabular}{ll";
  for (std::size_t i = 2; i < t.headers.size(); ++i) out += "r";
  out += "}\n\\toprule\n";
  for (std::size_t i = 0; i < t.headers.size(); ++i) out += (i ? " & " : "") + tex(t.headers[i]);
  out += " \\\\\n\\midrule\n";
  for (const auto& r : t.rows) {
    for (std::size_t i = 0; i < r.size(); ++i) out += (i ? " & " : "") + tex(r[i]);
    out += " \\\\\n";
  }
  out += "\\bottomrule\n\\end{tabular}\n\\caption{" + tex(caption) + "}\n\\end{table}\n";
  return out;
}

std::vector<json> load_run_records(const std::string& result_dir) {
  std::vector<json> out;
  const fs::path runs = fs::path(result_dir) / "runs";
  if (!fs::is_directory(runs)) throw FileError(result_dir, "not a result directory (no runs/ folder)");
  for (const auto& entry : fs::directory_iterator(runs)) {
    const fs::path m = entry.path() / "metrics.json";
    if (!fs::exists(m)) continue;  // a run that never finished
    std::ifstream in(m);
    try {
      out.push_back(json::parse(in));
    } catch (const json::exception& e) {
      throw FileError(m.string(), std::string("malformed JSON: ") + e.what());
    }
  }
  std::sort(out.begin(), out.end(), [](const json& a, const json& b) {
    return std::make_pair(a.value("order", 0), a.value("run", std::string())) <
           std::make_pair(b.value("order", 0), b.value("run", std::string()));
  });
  return out;
}

std::string write_tables(const std::string& result_dir, const std::vector<std::string>& columns,
                         const std::string& title) {
  const Table t = make_table(load_run_records(result_dir), columns);
  const std::string md = to_markdown(t);
  write_file_atomically(result_dir + "/table.md", [&](std::ostream& o) { o << "# " << title << "\n\n" << md; });
  write_file_atomically(result_dir + "/table.csv", [&](std::ostream& o) { o << to_csv(t); });
  write_file_atomically(result_dir + "/table.tex", [&](std::ostream& o) { o << to_latex(t, title); });
  return md;
}

}  // namespace dtsl
