#include "framework/pipeline/run_one.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"
#include "framework/io/io.hpp"
#include "framework/metrics/metrics.hpp"
#include "framework/pipeline/line_obj.hpp"
#include "framework/pipeline/preset.hpp"
#include "framework/pipeline/reconstructor.hpp"

namespace dtsl {

namespace fs = std::filesystem;

nlohmann::json measure_mesh(const TriangleMesh& mesh, const Dataset& dataset, const MetricsOptions* metrics,
                            std::uint64_t seed) {
  nlohmann::json j;
  j["mesh"] = to_json(mesh_stats(mesh));
  if (!mesh.faces.empty()) {
    j["point_errors"] = to_json(point_errors(dataset.points.points, mesh));
    if (metrics && dataset.ground_truth)
      j["surface"] = to_json(compare_surfaces(mesh, *dataset.ground_truth, static_cast<std::size_t>(metrics->samples),
                                              metrics->fscore_tau_ratio, seed));
  }
  return j;
}

nlohmann::json write_stage_files(const ReconstructionResult& result, const std::string& dir) {
  nlohmann::json stages = nlohmann::json::array();
  for (const StageRecord& s : result.stages) {
    nlohmann::json js = {{"name", s.name}, {"seconds", s.seconds}, {"summary", s.summary}};
    if (s.mesh) {
      const std::string label = s.mesh_label.empty() ? s.name : s.mesh_label;
      js["mesh_label"] = label;
      js["file"] = "stage_" + label + ".ply";
      write_mesh(dir + "/stage_" + label + ".ply", *s.mesh);
    }
    if (s.lines) {  // line geometry for figures (the T-mesh), atomically like the meshes
      const std::string file = s.lines->name + ".obj";
      const bool plain = !s.lines->name.empty() &&
                         std::all_of(s.lines->name.begin(), s.lines->name.end(), [](unsigned char c) {
                           return std::isalnum(c) || c == '_' || c == '-';
                         });
      if (!plain) throw AlgorithmError("stage " + s.name + ": line set name '" + s.lines->name + "' is not a plain file stem");
      write_line_obj(dir + "/" + file, s.lines->segments, s.lines->label + " of stage " + s.name);
      js["lines_file"] = file;
      js["lines_label"] = s.lines->label;
      js["lines_segments"] = s.lines->segments.size();
    }
    stages.push_back(js);
  }
  return stages;
}

nlohmann::json execute_run(const RunSpec& run, const Dataset& dataset, const MetricsOptions& metrics,
                           std::uint64_t seed, const std::string& run_dir, FilesFrame frame) {
  nlohmann::json record;
  record["run"] = run.id;
  record["dataset"] = run.dataset_name;
  record["pipeline"] = run.pipeline_name;
  record["type"] = run.pipeline_type;
  record["sweep"] = nlohmann::json::object();
  for (const auto& [k, v] : run.sweep) record["sweep"][k] = v;
  record["seed"] = seed;
  record["np"] = dataset.points.size();
  record["dataset_has_ground_truth"] = dataset.ground_truth.has_value();
  if (dataset.ground_truth)  // the truth's statistics as written with the dataset, else measured here
    record["truth_mesh"] = dataset.description.contains("ground_truth_mesh") ? dataset.description["ground_truth_mesh"]
                                                                             : to_json(mesh_stats(*dataset.ground_truth));
  Stopwatch total;
  try {
    auto pipeline = reconstructors().create(run.pipeline_type, run.id);
    const std::string preset = run.pipeline["preset"] ? run.pipeline["preset"].Scalar() : "default";
    apply_preset(*pipeline, run.pipeline_type, preset, run.id + ".preset");
    record["preset"] = preset;
    apply_yaml(pipeline->options(), run.pipeline["options"], run.id + ".options");
    record["options"] = to_json(pipeline->options());
    RunContext context;
    context.seed = seed;
    Stopwatch clock;
    ReconstructionResult result = pipeline->reconstruct(dataset.points, context);
    record["time_total"] = clock.seconds();
    record["peak_memory_mib"] = peak_memory_mib();
    record["summary"] = result.summary;

    // Measured in the [-1,1]^3 frame (the paper's errors), written in the files' frame.
    std::vector<nlohmann::json> measures(result.stages.size());
    for (std::size_t i = 0; i < result.stages.size(); ++i)
      if (result.stages[i].mesh)
        measures[i] = measure_mesh(*result.stages[i].mesh, dataset, metrics.stage_surfaces ? &metrics : nullptr, seed);
    record["final"] = measure_mesh(result.mesh, dataset, &metrics, seed);
    if (frame == FilesFrame::input) transform(result, dataset.normalisation.inverse());
    record["files_frame"] = frame == FilesFrame::input ? "input" : "normalised";

    fs::create_directories(run_dir);
    nlohmann::json stages = write_stage_files(result, run_dir);
    for (std::size_t i = 0; i < result.stages.size(); ++i)
      if (result.stages[i].mesh) stages[i]["measures"] = std::move(measures[i]);
    record["stages"] = stages;
    write_mesh(run_dir + "/final.ply", result.mesh);
    record["status"] = "ok";
  } catch (const std::exception& e) {
    // A failed run is a result: its table row says why (a bad_alloc is an out-of-memory failure).
    record["status"] = "failed";
    record["error"] = e.what();
  }
  record["time_wall"] = total.seconds();
  return record;
}

}  // namespace dtsl
