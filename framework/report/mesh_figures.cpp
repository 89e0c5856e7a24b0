#include "framework/report/mesh_figures.hpp"
#include "framework/pipeline/json_lookup.hpp"

#include <array>
#include <cstdio>

#include "framework/io/io.hpp"
#include "framework/pipeline/line_obj.hpp"
#include "framework/render/scene_figure.hpp"

namespace dtsl::report {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

/// A file a record names must sit in its run directory: an absolute path or one with a directory part
/// (a hand-edited or foreign metrics.json) would read files elsewhere.
bool plain_file_name(const std::string& file) {
  return !file.empty() && file != "." && file != ".." && fs::path(file).filename().string() == file;
}

constexpr auto fmt = format_json_number;

constexpr auto at = json_at;

}  // namespace

/// The run's pictures: ground truth, input points, then each stage mesh (or the final mesh).
render::Image run_renders(const fs::path& dir, const json& record, const std::string& dataset_key,
                          const ReportOptions& options) {
  const fs::path ddir = dir / "datasets" / dataset_key, rdir = dir / "runs" / record.value("run", std::string());
  std::vector<TriangleMesh> meshes;
  std::vector<std::string> labels;
  PointCloud points;
  meshes.reserve(8);
  if (fs::exists(ddir / "ground_truth.ply")) {
    meshes.push_back(read_mesh((ddir / "ground_truth.ply").string()));
    labels.push_back("ground truth");
  }
  if (fs::exists(ddir / "points.ply")) points = read_points((ddir / "points.ply").string());
  bool staged = false;
  // Line geometry a stage left (the T-mesh of dtsl runs): drawn over the points, the first picture of
  // the method's stages (the paper's Fig. 1a). Old results and baselines have none.
  std::vector<std::array<Vec3, 2>> lines;
  std::string lines_label;
  if (record.contains("stages") && record["stages"].is_array())
    for (const json& st : record["stages"]) {
      const std::string file = st.is_object() ? st.value("lines_file", std::string()) : std::string();
      if (!plain_file_name(file) || !lines_label.empty() || !fs::exists(rdir / file)) continue;
      lines = read_line_obj((rdir / file).string());
      lines_label = st.value("lines_label", std::string("lines"));
    }
  if (record.contains("stages") && record["stages"].is_array())
    for (const json& st : record["stages"]) {
      const std::string file = st.is_object() ? st.value("file", std::string()) : std::string();
      if (!plain_file_name(file) || !fs::exists(rdir / file) || meshes.size() >= 7) continue;
      meshes.push_back(read_mesh((rdir / file).string()));
      std::string label = st.value("mesh_label", st.value("name", std::string("?")));
      const json* e = at(st, {"measures", "point_errors", "e_avr"});
      if (e && e->is_number()) label += "  e_avr " + fmt(e, 1e3, "%.2f") + "e-3";
      labels.push_back(label);
      staged = true;
    }
  if (!staged && fs::exists(rdir / "final.ply")) {
    meshes.push_back(read_mesh((rdir / "final.ply").string()));
    std::string label = record.value("pipeline", std::string("final"));
    const json* e = at(record, {"final", "point_errors", "e_avr"});
    if (e && e->is_number()) label += "  e_avr " + fmt(e, 1e3, "%.2f") + "e-3";
    labels.push_back(label);
  }
  std::vector<render::SceneItem> items;
  std::size_t m = 0;
  if (!labels.empty() && labels[0] == "ground truth") items.push_back({labels[0], &meshes[m++], nullptr});
  if (!points.empty()) items.push_back({"points (" + std::to_string(points.size()) + ")", nullptr, &points.points});
  if (!lines_label.empty()) {
    // The last mesh (the result) hides the points and cells behind the surface: the cells around it
    // seen from both sides at once are a tangle.
    render::SceneItem t{(points.empty() ? "" : "points + ") + lines_label, nullptr, nullptr, &lines};
    if (!points.empty()) t.points = &points.points;
    if (m < meshes.size()) t.occluder = &meshes.back();
    items.push_back(t);
  }
  for (; m < meshes.size(); ++m) items.push_back({labels[m], &meshes[m], nullptr});
  if (items.empty()) return {};
  return render::render_scene(items, options.scene());
}

/// One picture per dataset: its points and the final mesh of every run on it (pipelines, sweep values)
/// side by side, same cameras: the comparison a results table stands for. At most 8 meshes.
render::Image dataset_comparison(const fs::path& dir, const std::string& dataset_key, const std::vector<const json*>& runs,
                                 const ReportOptions& options) {
  PointCloud points;
  if (fs::exists(dir / "datasets" / dataset_key / "points.ply"))
    points = read_points((dir / "datasets" / dataset_key / "points.ply").string());
  std::vector<TriangleMesh> meshes;
  std::vector<std::string> labels;
  meshes.reserve(8);
  for (const json* r : runs) {
    const fs::path f = dir / "runs" / r->value("run", std::string()) / "final.ply";
    if (meshes.size() >= 8 || !fs::exists(f)) continue;
    meshes.push_back(read_mesh(f.string()));
    std::string label = r->value("pipeline", std::string("?"));
    if (r->contains("sweep") && (*r)["sweep"].is_object())
      for (auto it = (*r)["sweep"].begin(); it != (*r)["sweep"].end(); ++it)
        label += " " + it.key().substr(it.key().find_last_of('.') + 1) + "=" + (it->is_string() ? it->get<std::string>() : it->dump());
    labels.push_back(label);
  }
  if (meshes.size() < 2) return {};
  std::vector<render::SceneItem> items;
  if (!points.empty()) items.push_back({"points (" + std::to_string(points.size()) + ")", nullptr, &points.points});
  for (std::size_t i = 0; i < meshes.size(); ++i) items.push_back({labels[i], &meshes[i], nullptr});
  return render::render_scene(items, options.scene());
}

}  // namespace dtsl::report
