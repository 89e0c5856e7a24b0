// Phase-1 benchmark (not a test; docs/performance.md): the level-set stage on fandisk cut by a plane (~6k scan
// vertices) and the bunny subsampled to 6k points, per solver: wall time, iterations, where the time
// goes, distances reached. Also times the solvers alone on one evolution step's least-squares system.
//
//   phase1_bench [--repeat N] [--solvers a,b,...] [--datasets fandisk,bunny] [--set key=value ...]
//
// Needs the libcgal-demo models in the data cache (scripts/fetch_data.sh; docs/design.md §7). Times are
// the best of N repeats (the machine is shared). Output: one JSON object per line.
#include <algorithm>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "algorithms/evolution/evolution.hpp"
#include "algorithms/evolution/initial_level_set.hpp"
#include "algorithms/evolution/least_squares_rows.hpp"
#include "algorithms/evolution/zero_set.hpp"
#include "framework/core/allocator.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/core/timer.hpp"
#include "framework/datasets/dataset.hpp"

using namespace dtsl;

namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

std::vector<Vec3> dataset(const std::string& name) {
  register_dataset_plugins();
  const std::string yaml =
      name == "fandisk"
          ? "{name: fandisk_cut, shape: {type: cgal_model, model: fandisk}, sampler: vertices, "
            "corruptions: [{type: plane_cut, normal: [0, 0, 1], offset: 0.75}]}"
          : "{name: bunny6k, shape: {type: cgal_model, model: bunny00}, sampler: vertices, "
            "corruptions: [{type: subsample, count: 6000}]}";
  DatasetSpec spec = parse_dataset(YAML::Load(yaml), name);
  return build_dataset(spec, 1).points.points;
}

/// The least-squares system of the first evolution step, for timing the solvers alone.
LeastSquaresSystem first_step_system(const std::vector<Vec3>& points, const EvolutionOptions& o) {
  auto basis = std::make_shared<TSplineBasis>(build_octree(points, o.tmesh));
  const TSpline f = initial_level_set(basis, points, o.initial_radius_factor, o.initial_box_margin);
  ZeroSetSampling sampling;
  sampling.subdivision = o.subdivision;
  sampling.band_subdivision = o.band_subdivision;
  sampling.band_width = o.band_width;
  const ZeroSetSamples s = sample_zero_set(f, basis->octree(), sampling);
  LeastSquaresBuilder rows(*basis);
  std::vector<Vec3> x;
  std::vector<double> target;
  for (const SurfacePoint& p : s.surface) {
    x.push_back(p.position);
    target.push_back(0.1 * p.gradient.norm());
  }
  rows.add_value_rows(x, target, 1.0);
  std::vector<Vec3> direction;
  std::vector<double> rhs;
  for (std::size_t m = 0; m < s.band.size(); ++m) {
    direction.push_back(2.0 * 0.2 * s.band_gradient[m]);
    rhs.push_back(1.0 - s.band_gradient[m].squaredNorm());
  }
  rows.add_gradient_rows(s.band, direction, rhs, o.w_distance);
  return rows.finish(o.w_smooth);
}

}  // namespace

int main(int argc, char** argv) {
  dtsl::configure_allocator();  // as `dtsl` does (framework/core/allocator.hpp)
  int repeat = 3;
  register_velocities();
  register_level_set_solvers();
  std::vector<std::string> solvers = level_set_solvers().names();
  std::vector<std::string> datasets = {"fandisk", "bunny"};
  std::vector<std::pair<std::string, std::string>> sets;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--repeat" && a + 1 < argc) repeat = std::max(1, std::atoi(argv[++a]));
    else if (arg == "--solvers" && a + 1 < argc) solvers = split(argv[++a]);
    else if (arg == "--datasets" && a + 1 < argc) datasets = split(argv[++a]);
    else if (arg == "--set" && a + 1 < argc) {
      const std::string kv = argv[++a];
      const auto eq = kv.find('=');
      sets.emplace_back(kv.substr(0, eq), eq == std::string::npos ? "" : kv.substr(eq + 1));
    } else {
      std::cerr << "usage: phase1_bench [--repeat N] [--solvers a,b] [--datasets fandisk,bunny] [--set key=value]\n";
      return 2;
    }
  }
  try {
    for (const std::string& name : datasets) {
      const std::vector<Vec3> points = dataset(name);
      EvolutionOptions base;
      // --set solver_KEY=VALUE: an option of the solvers of the one-step solve below; else of the stage.
      std::vector<std::pair<std::string, std::string>> solver_sets;
      for (const auto& [k, v] : sets) {
        if (k.rfind("solver_", 0) == 0) solver_sets.emplace_back(k.substr(7), v);
        else apply_assignment(base, k, v, "--set");
      }
      {
        const LeastSquaresSystem system = first_step_system(points, base);
        for (const std::string& solver_name : solvers) {
          auto solver = level_set_solvers().create(solver_name, "--solvers");
          for (const auto& [k, v] : solver_sets) apply_assignment(solver->options(), k, v, "--set solver_");
          double best = 1e300;
          SolveReport report;
          for (int r = 0; r < repeat; ++r) {
            Eigen::VectorXd u = Eigen::VectorXd::Zero(system.unknowns);
            report = solver->solve(system, u);
            best = std::min(best, report.seconds);
          }
          nlohmann::json j = {{"dataset", name},          {"what", "one step's solve"},
                              {"solver", solver_name},    {"seconds", best},
                              {"unknowns", system.unknowns}, {"rows", system.rows()},
                              {"nonzeros", system.nonzeros()}, {"report", to_json(report)}};
          std::cout << j.dump() << std::endl;
        }
      }
      for (const std::string& solver_name : solvers) {
        EvolutionOptions o = base;
        o.solver = solver_name;
        double best = 1e300;
        LevelSetResult kept = compute_level_set(points, o);
        for (int r = 1; r < repeat; ++r) {
          LevelSetResult result = compute_level_set(points, o);
          if (result.summary["seconds"].get<double>() < kept.summary["seconds"].get<double>()) kept = std::move(result);
        }
        best = kept.summary["seconds"].get<double>();
        nlohmann::json j = {{"dataset", name},
                            {"what", "phase 1"},
                            {"points", points.size()},
                            {"solver", solver_name},
                            {"velocity", o.velocity},
                            {"seconds", best},
                            {"tmesh_seconds", kept.summary["tmesh_seconds"]},
                            {"evolution_seconds", kept.summary["evolution_seconds"]},
                            {"evolution_timings", kept.summary["evolution_timings"]},
                            {"iterations", kept.summary["iterations"]},
                            {"stop_reason", kept.stop_reason},
                            {"control_points", kept.summary["tmesh"]["control_points"]},
                            {"mean_distance_evolved", kept.summary["mean_distance"]},
                            {"max_distance_evolved", kept.summary["max_distance"]}};
        if (kept.refinement) {
          j["refinement_seconds"] = kept.refinement->seconds;
          j["control_points_refined"] = kept.refinement->control_points_after;
          j["mean_distance_refined"] = kept.refinement->after.mean;
          j["max_distance_refined"] = kept.refinement->after.max;
        }
        std::cout << j.dump() << std::endl;
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "phase1_bench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
