// EvolutionOptions: the stage's own fields plus, under prefixes, the options of the chosen velocity
// plugins (evolution.hpp).
#include "algorithms/evolution/evolution.hpp"

#include <utility>
#include "framework/config/prefixed_visitor.hpp"
#include "framework/core/error.hpp"

namespace dtsl {

EvolutionOptions::EvolutionOptions() {
  register_velocities();
  register_level_set_solvers();
}

void EvolutionOptions::sync_plugins() const {
  if (!velocity_plugin_ || velocity_name_ != velocity) {
    velocity_plugin_ = velocities().create(velocity, "velocity");
    velocity_name_ = velocity;
  }
  if (fine_velocity.empty()) {
    fine_velocity_plugin_.reset();
    fine_velocity_name_.clear();
  } else if (!fine_velocity_plugin_ || fine_velocity_name_ != fine_velocity) {
    fine_velocity_plugin_ = velocities().create(fine_velocity, "fine_velocity");
    fine_velocity_name_ = fine_velocity;
  }
}

Velocity& EvolutionOptions::fine_velocity_plugin() {
  return const_cast<Velocity&>(std::as_const(*this).fine_velocity_plugin());
}
const Velocity& EvolutionOptions::fine_velocity_plugin() const {
  if (fine_velocity.empty()) throw ConfigError("fine_velocity: empty (the rounds use `velocity`)");
  sync_plugins();
  return *fine_velocity_plugin_;
}

void EvolutionOptions::use_velocity(const std::string& name, const Velocity& plugin) {
  velocity = name;
  velocity_name_ = name;
  velocity_plugin_ = plugin.clone();
}

Velocity& EvolutionOptions::velocity_plugin() {
  sync_plugins();
  return *velocity_plugin_;
}
const Velocity& EvolutionOptions::velocity_plugin() const {
  sync_plugins();
  return *velocity_plugin_;
}

// The options a user chooses between (each with a trade-off the suite or the paper shows); every other
// field of EvolutionOptions and of its parts is a constant of the method, documented where it is declared
// (evolution.hpp, octree.hpp, coarse_to_fine.hpp, final_refinement.hpp) and not read from configs.
void EvolutionOptions::visit(FieldVisitor& v) {
  v.field("velocity", velocity, "normal velocity plugin: geodesic, distance_balloon, distance or paper (its options: velocity_*)");
  v.field("fine_velocity", fine_velocity,
          "velocity of the coarse-to-fine rounds and of the one evolution from a carve or wrap initial level set "
          "(its options: fine_velocity_*; ours); empty: `velocity`. The first evolution approaches the data "
          "from the enclosing sphere, the others start near it");
  v.field("initial", initial,
          "initial level set: sphere (paper §2.1: the evolution changes the topology), wrap (ours: the data's alpha "
          "wrap decides it, one ball size; data_wrap.hpp) or carve (ours: a Delaunay carving whose ball follows the "
          "local spacing, which opens every gap between separate pieces of the data; data_carving.hpp)");
  v.field("wrap_alpha", wrap_alpha,
          "with initial: wrap or carve, the carving ball's radius in data spacings: holes and gaps narrower than about twice "
          "this stay closed (with carve, not gaps between separate pieces), sampling gaps wider than this let it into "
          "the solid");
  v.field("solver", solver,
          "least-squares solver plugin: eigen_ldlt, eigen_cg, ceres or cholmod (same meshes, different times: "
          "configs/ablation_evolution_solver.yaml)");
  v.field("tmesh_max_depth", tmesh.max_depth,
          "finest octree level of the T-mesh; cells per axis there = 2^max_depth (paper §2.1: <= 6): detail "
          "against time and memory");
  v.field("fine_levels", fine.levels,
          "refine-and-evolve rounds after the first evolution, one octree level each (ours; capped at "
          "tmesh_max_depth); 0: one evolution on the initial T-mesh, as the paper");
  v.field("final_refinement", final_refinement, "refine and fit the level set after the evolution (paper §2.1, [55])");
  v.field("max_points", max_points,
          "the level-set stage uses at most this many data points: a few spread over every finest T-mesh cell "
          "(thin_points.hpp: sparse cells keep all theirs; displacement and sharpening use all points); 0: all");
  sync_plugins();
  PrefixedVisitor velocity_fields(v, "velocity_");
  velocity_plugin_->options().visit(velocity_fields);
  if (fine_velocity_plugin_) {
    PrefixedVisitor fine_velocity_fields(v, "fine_velocity_");
    fine_velocity_plugin_->options().visit(fine_velocity_fields);
  }
}

void EvolutionOptions::check() const {
  if (!velocities().contains(velocity)) velocities().create(velocity, "velocity");  // throws, listing the names
  if (!fine_velocity.empty() && !velocities().contains(fine_velocity))
    velocities().create(fine_velocity, "fine_velocity");
  if (!level_set_solvers().contains(solver)) level_set_solvers().create(solver, "solver");
  check_non_negative("w_distance", w_distance);
  check_non_negative("w_smooth", w_smooth);
  check_range("cfl", cfl, 1e-3, 10.0);
  check_range("max_time_step", max_time_step, 1e-9, 100.0);
  check_range("max_iterations", max_iterations, 0, 100000);
  check_non_negative("velocity_tolerance", velocity_tolerance);
  check_range("distance_tolerance", distance_tolerance, 0.0, 1.0);
  check_range("patience", patience, 1, 100000);
  check_range("subdivision", subdivision, 1, 4);
  check_range("band_subdivision", band_subdivision, 1, 4);
  check_range("band_width", band_width, 0.5, 10.0);
  check_positive("curvature_clamp", curvature_clamp);
  check_range("sign_guard", sign_guard, 0.0, 10.0);
  require(initial == "sphere" || initial == "wrap" || initial == "carve", "initial",
          "must be sphere, wrap or carve, not '" + initial + "'");
  check_range("wrap_alpha", wrap_alpha, 0.5, 100.0);
  check_range("initial_radius_factor", initial_radius_factor, 1.0, 10.0);
  require(max_points == 0 || max_points >= 100, "max_points",
          "must be 0 (all points) or at least 100, got " + std::to_string(max_points));
  require(initial_box_margin < tmesh.margin, "initial_box_margin",
          "must be smaller than tmesh_margin (the initial surface must lie inside the T-mesh's domain), got " +
              std::to_string(initial_box_margin));
  checked_with_prefix("velocity_", [&] { velocity_plugin().options().check(); });
  if (!fine_velocity.empty())
    checked_with_prefix("fine_velocity_", [&] { fine_velocity_plugin().options().check(); });
  checked_with_prefix("tmesh_", [&] { tmesh.check(); });
  checked_with_prefix("fine_", [&] { fine.check(); });
  checked_with_prefix("refine_", [&] { refinement.check(); });
}

}  // namespace dtsl
