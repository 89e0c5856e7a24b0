// Phase 1 of the paper (§2.1, its ref. [55]; docs/design.md §1): the T-spline level set that captures the
// topology and outline of the data by itself.
//
//   T-mesh from the points (octree, algorithms/tspline) -> f_0 = distance to the enclosing sphere
//   (clipped to the data's box, initial_level_set.hpp) -> evolution df/dt + v |grad f| = 0 with the
//   distance-field constraint -> final refinement (final_refinement.hpp).
//
// Each step finds the coefficient derivatives c' by least squares (least_squares_rows.hpp)
//
//   E(c') = sum_j (f'(x_j) + v(x_j) |grad f(x_j)|)^2 / J
//         + w_D sum_m (2 dt grad f(y_m) . grad f'(y_m) + |grad f(y_m)|^2 - 1)^2 / M
//         + w_S |c'|^2 / n
//
// (x_j on the zero set, y_m in a band around it: zero_set.hpp), solved by a LevelSetSolver plugin,
// then takes the explicit Euler step c <- c + dt c' with a CFL step dt, guarded against zero crossings
// appearing away from the front (sign_guard.hpp). The distance-field term is the linearisation of
// |grad (f + dt f')| = 1 and replaces re-initialisation ([55]). Topology changes happen by themselves:
// the zero set is re-sampled over the whole T-mesh every step and nothing assumes a genus or a number
// of components.
//
// Stopping (docs/design.md §1, made two-sided, ours): the progress measure is the mean data-to-level-set
// distance |f(p)| / |grad f(p)| plus the mean level-set-to-data distance d(x_j); the evolution stops
// when mean |v| falls below velocity_tolerance ("at rest"), when that measure (averaged over the last
// two steps: `geodesic` jitters with period two) has not fallen by distance_tolerance for `patience`
// steps ("distance stalled") or has risen 2 % above the last value that fell by it ("distance rising":
// in the suite's evolutions the measure, once past its best, climbs and does not come back below it),
// at max_iterations ("iteration cap"), or when the zero set has vanished ("level set vanished": data
// with no volume). The iterate kept is the one with the smallest measure.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "algorithms/evolution/coarse_to_fine.hpp"
#include "algorithms/evolution/final_refinement.hpp"
#include "algorithms/evolution/solver.hpp"
#include "algorithms/evolution/thin_walls.hpp"
#include "algorithms/evolution/velocity.hpp"
#include "algorithms/tspline/tspline.hpp"
#include "framework/config/options.hpp"
#include "framework/core/clone_ptr.hpp"

namespace dtsl {

/// Every parameter of the level-set stage. Configs set only the few that are options (visit(): the
/// velocities with their own options under velocity_ and fine_velocity_, the solver, tmesh_max_depth,
/// fine_levels, final_refinement, max_points); the other fields are constants of the method, kept here
/// so that tests and the ablation benches can vary them. Plain copyable data: the velocities are values
/// (their options), and the least-squares solver is named here and created by the stage that runs it.
struct EvolutionOptions final : Options {
  std::string velocity = "distance_balloon";
  std::string fine_velocity;
  std::string solver = "eigen_cg";
  /// Weight w_D of the distance-field rows |grad(f + dt f')| = 1 (docs/design.md §1: 1; less fits the
  /// data closer but lets |grad f| collapse and adds handles: §8).
  double w_distance = 1.0;
  double w_smooth = 1e-3;                ///< weight w_S of the smoothness term |c'|^2 (docs/design.md)
  /// A step moves the zero set by at most cfl x the cell size: dt = cfl min_j h_j / |v_j|, h_j the leaf
  /// at x_j (big steps through coarse empty space).
  double cfl = 0.5;
  double max_time_step = 0.5;            ///< velocities ~ -(rate) d are Euler-monotone for dt <= 1 / rate
  int max_iterations = 200;              ///< iteration cap of the evolution
  double velocity_tolerance = 1e-3;      ///< at rest when the mean |v| on the zero set falls below this
  /// The distance between data and level set (mean both ways) counts as decreasing if it falls by this
  /// fraction; `patience` steps without that stop the evolution.
  double distance_tolerance = 1e-3;
  int patience = 3;
  int subdivision = 2;        ///< zero-set samples: centres of s^3 sub-cells of every leaf, projected onto f = 0
  int band_subdivision = 2;   ///< distance-field band samples: centres of b^3 sub-cells of every leaf
  double band_width = 2.0;    ///< band |f| / |grad f| < band_width x the leaf side (docs/design.md: 2 h_min)
  /// |kappa| is capped at curvature_clamp / leaf side: the T-mesh cannot carry finer curvature.
  double curvature_clamp = 2.0;
  /// No nucleation (sign_guard.hpp): a coefficient no zero-set row touches keeps its sign, at least this
  /// fraction of its cell size from zero (ours; 0 disables).
  double sign_guard = 0.25;
  /// The initial level set: "sphere" (paper §2.1; the enclosing sphere below), "wrap" (ours, data_wrap.hpp: the
  /// data's alpha wrap) or "carve" (ours, data_carving.hpp: a carving with a ball of the local spacing's size);
  /// with wrap or carve the T-mesh is refined toward the data before one evolution.
  std::string initial = "sphere";
  /// The wrap's or carving's ball radius in data spacings (data_wrap.hpp, data_carving.hpp): gaps and holes narrower than about twice this stay
  /// closed, openings of the sampling wider than this let the ball into the solid.
  double wrap_alpha = 3.0;
  double initial_radius_factor = 1.1;  ///< initial sphere radius over the data's largest distance from the box centre
  /// The initial sphere is clipped to the data's box grown by this, so that it starts inside the T-mesh's
  /// domain (ours; <= 0: the sphere alone).
  double initial_box_margin = 0.1;
  bool final_refinement = true;
  int max_points = 30000;
  TMeshOptions tmesh;
  CoarseToFineOptions fine;
  FinalRefinementOptions refinement;

  EvolutionOptions();

  void visit(FieldVisitor& v) override;
  void check() const override;

  /// The velocity plugin named by `velocity`, with its options (created anew with defaults when the
  /// name changed). ConfigError for an unknown name.
  Velocity& velocity_plugin();
  /// The coarse-to-fine rounds' velocity plugin named by `fine_velocity` (its options: fine_velocity_*);
  /// ConfigError when fine_velocity is empty (the rounds then use velocity_plugin()) or unknown.
  Velocity& fine_velocity_plugin();
  const Velocity& fine_velocity_plugin() const;
  /// Evolve with a copy of `plugin` (options included), registered as `name`, from now on.
  void use_velocity(const std::string& name, const Velocity& plugin);
  const Velocity& velocity_plugin() const;

 private:
  // A velocity plugin is its options plus a pure speed function: a value, copied with the struct
  // (ClonePtr). Created lazily for the names above, so that visit() reaches the chosen one's options.
  void sync_plugins() const;
  mutable std::string velocity_name_;  // the name velocity_plugin_ was created for
  mutable ClonePtr<Velocity> velocity_plugin_;
  mutable std::string fine_velocity_name_;
  mutable ClonePtr<Velocity> fine_velocity_plugin_;
};

/// One evolution step, measured before the step is taken (iteration 0 is the initial level set).
struct IterationRecord {
  int iteration = 0;
  int round = 0;                     ///< coarse-to-fine round (0: the initial T-mesh; coarse_to_fine.hpp)
  double seconds = 0.0;              ///< wall time since the evolution started, at the end of this step
  double time_step = 0.0;            ///< dt of the step taken (0 for the last record: no step)
  int surface_points = 0, band_points = 0, unknowns = 0;
  int guarded = 0;                   ///< coefficients the no-nucleation guard held (sign_guard.hpp)
  int held_walls = 0;                ///< walls whose middle the step held inside (thin_walls.hpp)
  int unsupported_points = 0;        ///< zero-set points spanning empty space (support.hpp)
  double mean_speed = 0.0, max_speed = 0.0;  ///< mean and max |v| over the x_j
  double mean_distance = 0.0, max_distance = 0.0;  ///< data to level set, |f(p)| / |grad f(p)|
  double mean_surface_distance = 0.0;  ///< level set to data: mean d(x_j) over the zero-set samples
  double min_gradient = 0.0, max_gradient = 0.0;   ///< |grad f| over the x_j
  double velocity_residual = 0.0;    ///< |A_v c' - b_v| / |b_v|: the part of the prescribed motion not realised
  std::optional<SolveReport> solve;  ///< none for the last record
};
nlohmann::json to_json(const IterationRecord& r);

/// Output of the stage: the level set, its history and the T-mesh (level_set_io.hpp writes them out).
struct LevelSetResult {
  TSpline level_set;                    ///< T-mesh and coefficients (after the final refinement if on)
  TSpline evolved;                      ///< the evolution's result before the final refinement
  std::vector<IterationRecord> history;
  int best_iteration = 0;  ///< the iterate kept: smallest mean_distance + mean_surface_distance
  /// "at rest", "distance stalled", "distance rising", "iteration cap", "level set vanished"
  std::string stop_reason;
  std::optional<RefinementReport> refinement;
  /// With the final refinement: `evolved` transferred onto level_set's T-mesh, before the fit.
  std::vector<double> transferred;
  nlohmann::json summary;               ///< options, counts, timings, stop reason, final distances
  /// The level set halfway through the first evolution (iteration best_iteration / 2 on the initial
  /// T-mesh): the paper's Fig. 1(b) "intermediate T-spline level set", for figures.
  std::optional<TSpline> midway;
};

/// The data points the level-set stage works on: thin_points() to options.max_points with the cell of the
/// T-mesh's finest level. AlgorithmError naming the first non-finite point (of all of them, kept or not).
std::vector<Vec3> level_set_data(const std::vector<Vec3>& points, const EvolutionOptions& options);

/// The whole stage: T-mesh from `points` (in the [-1,1]^3 frame; level_set_data() of them), initial sphere, evolution, the coarse-to-fine rounds (options.fine), final refinement. The history runs through all rounds. ConfigError for invalid options (naming the field, with its prefix); AlgorithmError for
/// input the stage cannot handle (fewer than 4 points, all points coinciding, non-finite or outside
/// the T-mesh's domain) or a solver failure.
LevelSetResult compute_level_set(const std::vector<Vec3>& points, const EvolutionOptions& options);

/// The evolution from a given level set (any T-mesh: adaptive, uniform, refined), then the final
/// refinement if options.final_refinement. options.tmesh and initial_radius_factor are not used.
/// `between_pieces`, when given, says which positions lie in a gap between separate pieces of the data:
/// the controls whose Greville point it holds stay positive (hold_outside, sign_guard.hpp). `walls`
/// (thin_walls.hpp, from a start the data decided) keep their middles inside.
LevelSetResult evolve_level_set(const TSpline& initial, const std::vector<Vec3>& points,
                                const EvolutionOptions& options,
                                const std::function<bool(const Vec3&)>& between_pieces = {},
                                const ThinWalls& walls = {});

}  // namespace dtsl
