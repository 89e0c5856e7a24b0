// Scaling benchmark (a command, not a test; docs/performance.md): the full `dtsl` pipeline against `pcl_poisson`
// (depth 8, ground-truth normals, so Poisson's time is a lower bound) on the same inputs — the paper-size
// inputs (fandisk cut, the holed 6k bunny, the 25k armadillo with noise and holes) and area samples of
// armadillo with noise at the sizes asked for — best of --repeat runs, each in a forked child so that
// its peak memory is its own.
//
//   scaling_bench [--sizes 10000,100000,1000000] [--repeat 3] [--paper-size] [--no-paper-size]
//                 [--timeout SECONDS per run]
//
// Output: one JSON object per (dataset, pipeline) on stdout, then a Markdown table with the per-phase
// times of dtsl, Poisson's time, their ratio, both peak memories, and what the time bought (dtsl's
// components and closedness, both chamfer distances to the ground truth, measured outside the clock). Needs the libcgal-demo models
// (scripts/fetch_data.sh). A second table: where dtsl's time goes inside its stages (the evolution's parts, the final
// refinement and its topology guard, the flip fallback's rounds), from the records the pipeline keeps.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "experiments/plugins.hpp"
#include "framework/core/allocator.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"
#include "framework/datasets/dataset.hpp"
#include "framework/metrics/metrics.hpp"
#include "framework/pipeline/reconstructor.hpp"

using namespace dtsl;
using json = nlohmann::json;

namespace {

struct Input {
  std::string name, yaml;
};

std::vector<Input> inputs(const std::vector<long>& sizes, bool paper_size) {
  std::vector<Input> in;
  if (paper_size) {
    in.push_back({"fandisk_cut", "{shape: {type: cgal_model, model: fandisk}, sampler: vertices, "
                                 "corruptions: [{type: plane_cut, normal: [0, 0, 1], offset: 0.75}]}"});
    in.push_back({"bunny_6k_holes", "{shape: {type: cgal_model, model: bunny00}, sampler: vertices, corruptions: "
                                    "[{type: subsample, count: 6000}, {type: holes, count: 4, radius: 0.08}]}"});
    in.push_back({"armadillo_25k", "{shape: {type: cgal_model, model: armadillo}, sampler: vertices, corruptions: "
                                   "[{type: noise, sigma: 0.002}, {type: holes, count: 6, radius: 0.06}]}"});
  }
  for (long n : sizes)
    in.push_back({"armadillo_area_" + std::to_string(n),
                  "{shape: {type: cgal_model, model: armadillo}, sampler: {type: area, count: " + std::to_string(n) +
                      "}, corruptions: [{type: noise, sigma: 0.002}]}"});
  return in;
}

/// One reconstruction in a child process: its stage times, total time and peak memory, or an error; after
/// the clock stops, what the time bought: components, watertight and the chamfer distance to the truth
/// (a fast wrong mesh is no result).
json run_in_child(const std::string& pipeline, const Dataset& data, int timeout) {
  const PointCloud& cloud = data.points;
  int fd[2];
  if (pipe(fd) != 0) throw Error("scaling_bench: pipe failed");
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    if (timeout > 0) alarm(timeout);  // SIGALRM ends the child: reported as "the child died (signal 14)"
    json out;
    try {
      auto r = reconstructors().create(pipeline, "pipeline");
      if (pipeline == "pcl_poisson") {
        apply_assignment(r->options(), "depth", "8", "pcl_poisson");
        apply_assignment(r->options(), "normals", "ground_truth", "pcl_poisson");
      }
      Stopwatch clock;
      const ReconstructionResult result = r->reconstruct(cloud, RunContext{});
      out["seconds"] = clock.seconds();
      alarm(0);  // the timeout is the reconstruction's; the metrics below are not timed
      for (const StageRecord& s : result.stages) {
        out["stages"][s.name] = s.seconds;
        // Where dtsl's time goes inside its stages (the records the pipeline keeps anyway).
        const nlohmann::json& m = s.summary;
        if (s.name == "TL" && m.contains("evolution_timings"))
          for (auto& [key, value] : m["evolution_timings"].items()) out["parts"]["evolution_" + key] = value;
        if (s.name == "TL" && m.contains("final_refinement")) out["parts"]["final_refinement"] = m["final_refinement"]["seconds"];
        if (s.name == "TL" && m.contains("refinement_guard")) out["parts"]["refinement_guard"] = m["refinement_guard"]["seconds"];
        if (s.name == "D-Map" && m.contains("refinement_round_seconds")) {
          double rounds = 0.0;
          for (const auto& round : m["refinement_round_seconds"])
            for (auto& [key, value] : round.items()) rounds += value.get<double>();
          out["parts"]["flip_refinement_rounds"] = rounds;
        }
      }
      out["vertices"] = result.mesh.vertices.size();
      out["peak_memory_mib"] = peak_memory_mib();
      out["allocator"] = allocator_configuration();
      try {  // a mesh the metrics refuse is still a timed run: say why, keep the time
        const MeshStats stats = mesh_stats(result.mesh);
        out["components"] = stats.components;
        out["watertight"] = stats.watertight;
        if (data.ground_truth)
          out["chamfer"] = compare_surfaces(result.mesh, *data.ground_truth, 100000, 0.005, 1).chamfer;
      } catch (const std::exception& e) {
        out["metrics_error"] = e.what();
      }
    } catch (const std::exception& e) {
      out["error"] = e.what();
    }
    const std::string text = out.dump();
    if (write(fd[1], text.data(), text.size()) < 0) _exit(2);
    _exit(0);
  }
  close(fd[1]);
  std::string text;
  char buf[4096];
  for (ssize_t n; (n = read(fd[0], buf, sizeof buf)) > 0;) text.append(buf, n);
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (text.empty()) return {{"error", "the child died (signal " + std::to_string(WIFSIGNALED(status) ? WTERMSIG(status) : 0) + ")"}};
  return json::parse(text);
}

std::vector<long> parse_sizes(const std::string& s) {
  std::vector<long> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(std::stol(item));
  return out;
}

std::string fixed(const json& j, const char* key, const char* fmt = "%.2f") {
  if (!j.contains(key) || !j[key].is_number()) return "–";
  char b[32];
  std::snprintf(b, sizeof b, fmt, j[key].get<double>());
  return b;
}

std::string thousandths(const json& j, const char* key) {
  if (!j.contains(key) || !j[key].is_number()) return "–";
  char b[32];
  std::snprintf(b, sizeof b, "%.2f", 1e3 * j[key].get<double>());
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  dtsl::configure_allocator();  // as `dtsl` does (framework/core/allocator.hpp)
  std::vector<long> sizes = {10000, 100000, 1000000};
  int repeat = 3, timeout = 0;
  bool paper_size = true;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--sizes" && a + 1 < argc) sizes = parse_sizes(argv[++a]);
    else if (arg == "--repeat" && a + 1 < argc) repeat = std::max(1, std::atoi(argv[++a]));
    else if (arg == "--no-paper-size") paper_size = false;
    else if (arg == "--paper-size") paper_size = true;
    else if (arg == "--timeout" && a + 1 < argc) timeout = std::atoi(argv[++a]);
    else {
      std::cerr << "usage: scaling_bench [--sizes 10000,100000,1000000] [--repeat N] [--no-paper-size] "
                   "[--timeout SECONDS]\n";
      return 2;
    }
  }
  try {
    register_all_plugins();
    register_dataset_plugins();
    std::vector<json> rows;
    for (const Input& input : inputs(sizes, paper_size)) {
      DatasetSpec spec = parse_dataset(YAML::Load("{name: " + input.name + ", " + input.yaml.substr(1)), input.name);
      const Dataset data = build_dataset(spec, 1);
      json row = {{"dataset", input.name}, {"points", data.points.size()}};
      for (const std::string pipeline : {"dtsl", "pcl_poisson"}) {
        json best;
        for (int r = 0; r < repeat; ++r) {
          json run = run_in_child(pipeline, data, timeout);
          if (run.contains("error")) {
            best = run;
            break;
          }
          if (best.is_null() || run["seconds"].get<double>() < best["seconds"].get<double>()) best = run;
        }
        json line = {{"dataset", input.name}, {"points", data.points.size()}, {"pipeline", pipeline},
                     {"repeat", repeat}, {"best", best}};
        std::cout << line.dump() << std::endl;
        row[pipeline] = best;
      }
      if (row["dtsl"].contains("seconds") && row["pcl_poisson"].contains("seconds"))
        row["ratio"] = row["dtsl"]["seconds"].get<double>() / row["pcl_poisson"]["seconds"].get<double>();
      rows.push_back(row);
    }
    std::cout << "\n| dataset | points | TL (s) | MT (s) | D-Map (s) | B-Evl (s) | dtsl (s) | dtsl peak (MiB) | "
                 "Poisson (s) | Poisson peak (MiB) | dtsl / Poisson | dtsl comp. | dtsl closed | chamfer dtsl / Poisson "
                 "(1e-3) |\n| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    for (const json& r : rows) {
      const json& d = r["dtsl"];
      const json stages = d.contains("stages") ? d["stages"] : json::object();
      std::cout << "| " << r["dataset"].get<std::string>() << " | " << r["points"] << " | " << fixed(stages, "TL")
                << " | " << fixed(stages, "MT") << " | " << fixed(stages, "D-Map") << " | " << fixed(stages, "B-Evl")
                << " | " << (d.contains("error") ? "failed" : fixed(d, "seconds")) << " | "
                << fixed(d, "peak_memory_mib", "%.0f") << " | " << fixed(r["pcl_poisson"], "seconds") << " | "
                << fixed(r["pcl_poisson"], "peak_memory_mib", "%.0f") << " | " << fixed(r, "ratio") << " | "
                << (d.contains("components") ? std::to_string(d["components"].get<int>()) : "–") << " | "
                << (d.contains("watertight") ? (d["watertight"].get<bool>() ? "yes" : "no") : "–") << " | "
                << thousandths(d, "chamfer") << " / " << thousandths(r["pcl_poisson"], "chamfer") << " |\n";
    }
    // Inside dtsl's best run: the evolution's parts (TL), the final refinement and its topology guard
    // (TL), the flip fallback's refine-and-retriangulate rounds (D-Map).
    std::cout << "\n| dataset | evolution (s) | solve (s) | forming normal eq. (s) | rows (s) | zero-set sampling (s) | "
                 "data fit (s) | final refinement (s) | refinement guard (s) | D-Map flip rounds (s) |\n"
                 "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    for (const json& r : rows) {
      const json& d = r["dtsl"];
      const json parts = d.contains("parts") ? d["parts"] : json::object();
      double evolution = 0.0;
      for (const char* k : {"evolution_solve", "evolution_rows", "evolution_zero_set_sampling", "evolution_data_fit",
                            "evolution_velocity"})
        if (parts.contains(k)) evolution += parts[k].get<double>();
      std::cout << "| " << r["dataset"].get<std::string>() << " | " << (parts.empty() ? "–" : fixed(json{{"e", evolution}}, "e"))
                << " | " << fixed(parts, "evolution_solve") << " | " << fixed(parts, "evolution_solve_normal_equations")
                << " | " << fixed(parts, "evolution_rows") << " | " << fixed(parts, "evolution_zero_set_sampling")
                << " | " << fixed(parts, "evolution_data_fit") << " | " << fixed(parts, "final_refinement") << " | "
                << fixed(parts, "refinement_guard") << " | " << fixed(parts, "flip_refinement_rounds") << " |\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "scaling_bench: " << e.what() << "\n";
    return 1;
  }
}
