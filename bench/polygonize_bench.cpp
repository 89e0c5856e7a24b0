// Triangles per second of every polygonizer on Phase-1 level sets of fandisk cut by a plane and the 6k
// bunny (docs/performance.md). Not a test:  build/bench/polygonize_bench [repeats]
// Prints one JSON line per (dataset, polygonizer, step): best wall time of `repeats` runs.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "algorithms/evolution/evolution.hpp"
#include "algorithms/polygonize/polygonizer.hpp"
#include "framework/core/allocator.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/core/timer.hpp"
#include "framework/datasets/dataset.hpp"
#include "experiments/plugins.hpp"

using namespace dtsl;

int main(int argc, char** argv) {
  dtsl::configure_allocator();  // as `dtsl` does (framework/core/allocator.hpp)
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  register_all_plugins();
  const char* specs[] = {
      "{name: fandisk_cut, shape: {type: cgal_model, model: fandisk}, sampler: vertices,"
      " corruptions: [{type: plane_cut, normal: [0, 0, 1], offset: 0.75}]}",
      "{name: bunny_6k, shape: {type: cgal_model, model: bunny00}, sampler: vertices,"
      " corruptions: [{type: subsample, count: 6000}]}"};
  for (const char* text : specs) {
    DatasetSpec spec = parse_dataset(YAML::Load(text), "bench");
    const Dataset data = build_dataset(spec, 1);
    const LevelSetResult level = compute_level_set(data.points.points, EvolutionOptions());
    const Octree& tree = level.level_set.tmesh();
    const double l_t = std::sqrt(3.0) * tree.unit() * std::pow(2.0, tree.max_depth() - tree.finest_leaf_level());
    for (const double step : {0.2 * l_t, 0.01})
      for (const std::string& name : polygonizers().names()) {
        double best = 1e300;
        std::size_t faces = 0;
        for (int r = 0; r < repeats; ++r) {
          auto p = polygonizers().create(name, "bench");
          Stopwatch clock;
          const PolygonizeResult result = p->polygonize(level.level_set, data.points.points, step);
          best = std::min(best, clock.seconds());
          faces = result.mesh.faces.size();
        }
        nlohmann::json line = {{"dataset", spec.name}, {"polygonizer", name}, {"step", step},
                               {"triangles", faces}, {"seconds", best},
                               {"triangles_per_second", faces / best}};
        std::cout << line.dump() << std::endl;
      }
  }
  return 0;
}
