#include "framework/report/report.hpp"
#include "framework/pipeline/json_lookup.hpp"

#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "framework/core/atomic_file.hpp"
#include "framework/core/error.hpp"
#include "framework/pipeline/experiment.hpp"
#include "framework/pipeline/tables.hpp"
#include "framework/render/png.hpp"
#include "framework/report/mesh_figures.hpp"
#include "framework/report/metric_charts.hpp"

namespace dtsl::report {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

std::string safe(const std::string& s) {
  std::string out;
  for (char c : s) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_') ? c : '_';
  return out;
}

std::string yaml_text(const YAML::Node& n) {
  if (n.IsScalar()) return n.Scalar();
  YAML::Emitter e;
  e << n;
  return e.c_str();
}

constexpr auto fmt = format_json_number;

constexpr auto at = json_at;

void commit_figures(const fs::path& tmp, const fs::path& figures) {
  const fs::path old = figures.string() + ".old-" + std::to_string(::getpid());
  if (fs::exists(figures)) fs::rename(figures, old);
  fs::rename(tmp, figures);
  std::error_code ec;
  fs::remove_all(old, ec);
}

}  // namespace

render::Image compose(const std::vector<render::Image>& images, int columns) {
  if (images.empty()) return {};
  columns = std::max(1, std::min<int>(columns, images.size()));
  const int rows = (static_cast<int>(images.size()) + columns - 1) / columns;
  std::vector<int> col_w(columns, 0), row_h(rows, 0);
  for (std::size_t i = 0; i < images.size(); ++i) {
    col_w[i % columns] = std::max(col_w[i % columns], images[i].width());
    row_h[i / columns] = std::max(row_h[i / columns], images[i].height());
  }
  int W = 0, H = 0;
  for (int w : col_w) W += w;
  for (int h : row_h) H += h;
  render::Image out(W, H);
  for (std::size_t i = 0; i < images.size(); ++i) {
    int x = 0, y = 0;
    for (std::size_t c = 0; c < i % columns; ++c) x += col_w[c];
    for (std::size_t r = 0; r < i / columns; ++r) y += row_h[r];
    out.paste(images[i], x, y);
  }
  return out;
}

ReportSummary write_report(const std::string& result_dir, const ReportOptions& options) {
  options.check();
  const fs::path dir(result_dir);
  if (!fs::is_directory(dir)) throw FileError(result_dir, "no such directory");
  if (!fs::is_regular_file(dir / "config.yaml") || !fs::is_directory(dir / "runs"))
    throw FileError(result_dir, "not a result directory (needs config.yaml and runs/, as `dtsl run` writes)");
  const Experiment ex = load_experiment((dir / "config.yaml").string(), {});
  const std::vector<json> records = load_run_records(result_dir);
  if (records.empty()) throw FileError(result_dir, "no finished run (no runs/*/metrics.json) to report on");
  std::map<std::string, std::string> dataset_key;
  for (const RunSpec& r : ex.runs) dataset_key[r.id] = r.dataset_key;
  fs::path normal = fs::absolute(dir).lexically_normal();
  if (normal.filename().empty()) normal = normal.parent_path();  // "DIR/"
  std::string run_id = normal.filename().string();

  const fs::path tmp = dir / ("figures.tmp-" + std::to_string(::getpid()));
  ReportSummary summary;
  summary.report_path = (dir / "report.md").string();
  std::ostringstream md;
  try {
    fs::remove_all(tmp);
    fs::create_directories(tmp);
    auto save = [&](const render::Image& img, const std::string& rel) {
      fs::create_directories((tmp / rel).parent_path());
      render::write_png((tmp / rel).string(), img);
      ++summary.figures;
      return "figures/" + rel;
    };

    std::ostringstream head;
    if (fs::exists(dir / "provenance.json")) {
      std::ifstream in(dir / "provenance.json");
      try {
        const json p = json::parse(in);
        if (p.contains("run_id") && p["run_id"].is_string()) run_id = p["run_id"].get<std::string>();
        head << "Commit `" << p.value("git_commit", std::string("?")) << "`" << (p.value("git_dirty", false) ? " (dirty)" : "")
           << ", started " << p.value("started_utc", std::string("?")) << ", seed " << ex.seed;
        if (p.contains("machine") && p["machine"].is_object())
          head << ", on " << p["machine"].value("cpu", std::string("?")) << " (" << p["machine"].value("cores", 0) << " cores)";
        if (p.contains("merged_from")) head << "; merged from " << p["merged_from"].size() << " shards";
        head << ".\n\n";
      } catch (const json::exception&) {
      }
    }
    md << "# " << ex.name << " (" << run_id << ")\n\n";
    if (!ex.description.empty()) md << ex.description << "\n\n";
    md << head.str();
    md << "## Table\n\n" << to_markdown(make_table(records, ex.table_columns)) << "\n";
    md << "Errors x 10^-3 in the [-1,1]^3 frame; MI / MD / MS = initial, displaced, sharpened mesh; "
          "TL, MT, D-Map, B-Evl = the phases' seconds.\n\n";

    md << "## Time per run\n\n![time per run](" << save(time_overview_chart(records, ex.name + ": time per run (s)").draw(), "times.png")
       << ")\n\n";

    if (!ex.sweep.empty()) {
      md << "## Sweeps\n\n";
      for (const SweepAxis& axis : ex.sweep) {
        std::vector<std::string> values;
        for (const YAML::Node& v : axis.values) values.push_back(yaml_text(v));
        std::vector<render::Image> charts;
        for (const SweepMetric& m : sweep_metrics())
          if (m.name != "e_max") charts.push_back(sweep_chart(records, axis.key, values, m).draw());
        md << "### " << axis.key << "\n\n![" << axis.key << "](" << save(compose(charts, 2), "sweep_" + safe(axis.key) + ".png")
           << ")\n\n";
      }
    }

    if (options.renders) {  // the final meshes of every run on a dataset, side by side
      std::vector<std::string> keys;
      std::map<std::string, std::vector<const json*>> by_key;
      for (const json& r : records) {
        const std::string id = r.value("run", std::string());
        if (!dataset_key.count(id)) continue;
        if (!by_key.count(dataset_key[id])) keys.push_back(dataset_key[id]);
        by_key[dataset_key[id]].push_back(&r);
      }
      bool header = false;
      for (const std::string& key : keys) {
        const render::Image img = dataset_comparison(dir, key, by_key[key], options);
        if (img.width() == 0) continue;
        if (!header) md << "## Final meshes by dataset\n\n", header = true;
        md << "### " << key << "\n\n![final meshes on " << key << "](" << save(img, "compare_" + key + ".png") << ")\n\n";
      }
    }

    md << "## Runs\n\n";
    std::size_t done = 0;
    for (const json& r : records) {
      const std::string id = r.value("run", std::string("?"));
      if (options.progress) std::cerr << "[" << ++done << "/" << records.size() << "] " << id << "\n";
      md << "### " << id << "\n\n";
      md << "Status **" << r.value("status", std::string("?")) << "**";
      if (r.value("status", std::string()) != "ok") md << ": " << r.value("error", std::string());
      else
        md << "; e_avr " << fmt(at(r, {"final", "point_errors", "e_avr"}), 1e3, "%.2f") << ", e_max "
           << fmt(at(r, {"final", "point_errors", "e_max"}), 1e3, "%.2f") << ", chamfer "
           << fmt(at(r, {"final", "surface", "chamfer"}), 1e3, "%.2f") << " (x 1e-3), F-score "
           << fmt(at(r, {"final", "surface", "fscore"}), 1, "%.3f") << ", " << fmt(at(r, {"final", "mesh", "vertices"}), 1, "%.0f")
           << " vertices, " << fmt(at(r, {"time_total"}), 1, "%.2f") << " s";
      md << ".\n\n";
      if (options.renders && dataset_key.count(id)) {
        const render::Image img = run_renders(dir, r, dataset_key[id], options);
        if (img.width() > 0) md << "![renders of " << id << "](" << save(img, id + "/renders.png") << ")\n\n";
      }
      const std::vector<render::LineChart> conv = convergence_charts(r);
      std::vector<render::Image> imgs;
      for (const render::LineChart& c : conv) imgs.push_back(c.draw());
      if (!imgs.empty()) md << "![convergence of " << id << "](" << save(compose(imgs, 2), id + "/convergence.png") << ")\n\n";
      if (r.value("type", std::string()) == "dtsl" && !has_evolution_history(r))
        md << "_No per-iteration history of the level-set evolution in this record (stages[TL].summary.history)._\n\n";
      const render::BarChart times = stage_time_chart(r);
      if (!times.rows.empty()) md << "![time per stage of " << id << "](" << save(times.draw(), id + "/timing.png") << ")\n\n";
    }
    summary.runs = records.size();
    commit_figures(tmp, dir / "figures");
    write_file_atomically(summary.report_path, [&](std::ostream& o) { o << md.str(); });
  } catch (...) {
    std::error_code ec;
    fs::remove_all(tmp, ec);
    throw;
  }
  return summary;
}

}  // namespace dtsl::report
