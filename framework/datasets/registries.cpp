// The three dataset registries and their one-time registration.
#include "framework/datasets/dataset.hpp"
#include "framework/datasets/internal.hpp"

namespace dtsl {

Registry<ShapeSource>& shape_sources() {
  static Registry<ShapeSource> registry("shape");
  return registry;
}

Registry<Sampler>& samplers() {
  static Registry<Sampler> registry("sampler");
  return registry;
}

Registry<Corruption>& corruptions() {
  static Registry<Corruption> registry("corruption");
  return registry;
}

void register_dataset_plugins() {
  // A second registration of a name is an error in Registry::add, so guard the whole set: tests and
  // the command line may both call this.
  static const bool done = [] {
    dataset_detail::register_synthetic_shapes();
    dataset_detail::register_block_shape();
    dataset_detail::register_plate_shapes();
    dataset_detail::register_lattice_shape();
    dataset_detail::register_pair_shape();
    dataset_detail::register_dumbbell_shape();
    dataset_detail::register_model_shapes();
    dataset_detail::register_samplers();
    dataset_detail::register_corruptions();
    return true;
  }();
  (void)done;
}

}  // namespace dtsl
