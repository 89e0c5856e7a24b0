#include "experiments/plugins.hpp"

#include "algorithms/baselines/baselines.hpp"
#include "algorithms/displacement/displacement.hpp"
#include "algorithms/method/dtsl_pipeline.hpp"
#include "algorithms/polygonize/polygonizer.hpp"
#include "algorithms/sharpen/sharpen_solver.hpp"
#include "framework/datasets/dataset.hpp"

namespace dtsl {

void register_all_plugins() {
  static bool done = false;
  if (done) return;
  done = true;
  register_dataset_plugins();
  register_baselines();
  register_polygonizers();
  register_displacers();
  sharpen::register_sharpen_solvers();
  register_dtsl_pipeline();
}

}  // namespace dtsl
