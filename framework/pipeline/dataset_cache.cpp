#include "framework/pipeline/dataset_cache.hpp"

#include <filesystem>
#include <fstream>

#include "framework/core/atomic_file.hpp"
#include "framework/core/error.hpp"
#include "framework/io/io.hpp"
#include "framework/metrics/metrics.hpp"

namespace dtsl {

namespace fs = std::filesystem;

void write_dataset(const std::string& dir, const Dataset& dataset) {
  fs::create_directories(dir);
  write_points(dir + "/points.ply", dataset.points);
  if (dataset.ground_truth) write_mesh(dir + "/ground_truth.ply", *dataset.ground_truth);
  nlohmann::json j = dataset.description;
  j["name"] = dataset.name;
  j["points"] = dataset.points.size();
  j["has_ground_truth"] = dataset.ground_truth.has_value();
  // Once per dataset: the truth's topology, which every run's record carries for the truth_genus,
  // truth_components and topology_ok columns.
  if (dataset.ground_truth) j["ground_truth_mesh"] = to_json(mesh_stats(*dataset.ground_truth));
  write_file_atomically(dir + "/dataset.json", [&](std::ostream& out) { out << j.dump(2) << "\n"; });
}

bool dataset_complete(const std::string& dir) { return fs::exists(dir + "/dataset.json"); }

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
  d.points = read_points(dir + "/points.ply");
  if (d.description.value("has_ground_truth", false)) d.ground_truth = read_mesh(dir + "/ground_truth.ply");
  return d;
}

}  // namespace dtsl
