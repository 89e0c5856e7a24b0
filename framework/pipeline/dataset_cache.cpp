#include "framework/pipeline/dataset_cache.hpp"

#include <cmath>
#include <filesystem>
#include <optional>
#include <fstream>

#include "framework/core/atomic_file.hpp"
#include "framework/core/error.hpp"
#include "framework/io/io.hpp"
#include "framework/metrics/metrics.hpp"

namespace dtsl {

namespace fs = std::filesystem;

namespace {
Similarity similarity_from_json(const nlohmann::json& j, const std::string& file) {
  try {
    const auto& c = j.at("center");
    Similarity s{Vec3(c.at(0).get<double>(), c.at(1).get<double>(), c.at(2).get<double>()), j.at("scale").get<double>()};
    if (!s.center.allFinite() || !(s.scale > 0.0) || !std::isfinite(s.scale)) throw std::domain_error("not finite");
    return s;
  } catch (const std::exception& e) {
    throw FileError(file, std::string("normalisation.input_to_points: expected {center: [x, y, z], scale: s > 0}: ") +
                              e.what());
  }
}
}  // namespace

void write_dataset(const std::string& dir, const Dataset& dataset, FilesFrame frame) {
  fs::create_directories(dir);
  PointCloud points = dataset.points;
  std::optional<TriangleMesh> truth = dataset.ground_truth;
  if (frame == FilesFrame::input) {
    transform(points, dataset.normalisation.inverse());
    if (truth) transform(*truth, dataset.normalisation.inverse());
  }
  write_points(dir + "/points.ply", points);
  if (truth) write_mesh(dir + "/ground_truth.ply", *truth);
  // The exact coordinates the runs see: mapping the input-unit files back would perturb them by rounding,
  // and the evolution is sensitive enough for that to show in the tables.
  if (frame == FilesFrame::input) {
    fs::create_directories(dir + "/normalised");
    write_points(dir + "/normalised/points.ply", dataset.points);
    if (dataset.ground_truth) write_mesh(dir + "/normalised/ground_truth.ply", *dataset.ground_truth);
  }
  nlohmann::json j = dataset.description;
  j["files_frame"] = frame == FilesFrame::input ? "input" : "normalised";
  j["input_to_files"] = to_json(frame == FilesFrame::input ? Similarity{} : dataset.normalisation);
  j["name"] = dataset.name;
  j["points"] = dataset.points.size();
  j["has_ground_truth"] = dataset.ground_truth.has_value();
  // Once per dataset: the truth's topology, which every run's record carries for the truth_genus,
  // truth_components and topology_ok columns.
  if (dataset.ground_truth) j["ground_truth_mesh"] = to_json(mesh_stats(*dataset.ground_truth));
  write_file_atomically(dir + "/dataset.json", [&](std::ostream& out) { out << j.dump(2) << "\n"; });
}

bool dataset_complete(const std::string& dir, FilesFrame frame) {
  std::ifstream in(dir + "/dataset.json");
  if (!in) return false;
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded()) return false;
  return j.value("files_frame", std::string("normalised")) == (frame == FilesFrame::input ? "input" : "normalised");
}

Dataset read_dataset(const std::string& dir) {
  const std::string meta = dir + "/dataset.json";
  std::ifstream in(meta);
  if (!in) throw FileError(meta, "missing: the dataset was not completely written");
  Dataset d;
  try {
    d.description = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw FileError(meta, std::string("malformed JSON: ") + e.what());
  }
  d.name = d.description.value("name", fs::path(dir).filename().string());
  // Folders without the keys were written in the [-1,1]^3 frame with an unknown normalisation.
  const nlohmann::json& n = d.description.value("normalisation", nlohmann::json::object());
  if (n.contains("input_to_points")) d.normalisation = similarity_from_json(n["input_to_points"], meta);
  const std::string frame = d.description.value("files_frame", std::string("normalised"));
  if (frame != "input" && frame != "normalised")
    throw FileError(meta, "files_frame: '" + frame + "' is neither 'input' nor 'normalised'");
  const std::string data = frame == "input" ? dir + "/normalised" : dir;
  d.points = read_points(data + "/points.ply");
  if (d.description.value("has_ground_truth", false)) d.ground_truth = read_mesh(data + "/ground_truth.ply");
  return d;
}

}  // namespace dtsl
