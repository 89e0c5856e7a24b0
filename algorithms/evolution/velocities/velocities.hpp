// Registration hooks of the velocity plugins, one per file of this folder (called by
// register_velocities()).
#pragma once

#include "algorithms/evolution/velocity.hpp"

namespace dtsl {

void add_distance_velocity(Registry<Velocity>& registry);
void add_geodesic_velocity(Registry<Velocity>& registry);
void add_distance_balloon_velocity(Registry<Velocity>& registry);

/// The common shape of a velocity plugin: its options and the speed formula.
template <class OptionsType, class Derived>
class VelocityWith : public Velocity {
 public:
  Options& options() override { return options_; }
  const Options& options() const override { return options_; }
  std::unique_ptr<Velocity> clone() const override {
    return std::make_unique<Derived>(static_cast<const Derived&>(*this));
  }
  OptionsType& typed_options() { return options_; }

 protected:
  OptionsType options_;
};

}  // namespace dtsl
