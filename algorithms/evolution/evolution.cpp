#include "algorithms/evolution/evolution.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>

#include "algorithms/evolution/data_distance.hpp"
#include "algorithms/evolution/support.hpp"
#include "algorithms/evolution/data_fit.hpp"
#include "algorithms/evolution/data_carving.hpp"
#include "algorithms/evolution/data_pieces.hpp"
#include "algorithms/evolution/data_wrap.hpp"
#include "algorithms/evolution/enclosed_volume.hpp"
#include "algorithms/evolution/gap_refinement.hpp"
#include "algorithms/evolution/initial_level_set.hpp"
#include "algorithms/evolution/least_squares_rows.hpp"
#include "algorithms/evolution/sign_guard.hpp"
#include "algorithms/evolution/thin_points.hpp"
#include "algorithms/evolution/thin_walls.hpp"
#include "algorithms/evolution/zero_set.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"

namespace dtsl {

namespace {
// In the suite's evolutions the progress measure (two-step mean), once past its best, climbs and does
// not come back below it. A rise of more than this fraction above its reference (the last value that
// fell by distance_tolerance) ends the evolution at once instead of after `patience` steps. Replayed on
// the histories of results/suite_{dev,test}/carve_default: 1 % and 2 % keep every kept iterate, 0.5 %
// stops the anchor 11 steps early; 2 % saves 17 % of the dev half's steps (docs/design.md §8).
constexpr double kDistanceRise = 0.02;
}  // namespace

nlohmann::json to_json(const IterationRecord& r) {
  nlohmann::json j = {{"iteration", r.iteration},
                      {"round", r.round},
                      {"seconds", r.seconds},
                      {"time_step", r.time_step},
                      {"surface_points", r.surface_points},
                      {"band_points", r.band_points},
                      {"unknowns", r.unknowns},
                      {"guarded", r.guarded},
                      {"held_walls", r.held_walls},
                      {"unsupported_points", r.unsupported_points},
                      {"velocity_residual", r.velocity_residual},
                      {"mean_speed", r.mean_speed},
                      {"max_speed", r.max_speed},
                      {"mean_distance", r.mean_distance},
                      {"max_distance", r.max_distance},
                      {"mean_surface_distance", r.mean_surface_distance},
                      {"min_gradient", r.min_gradient},
                      {"max_gradient", r.max_gradient}};
  if (r.solve) j["solve"] = to_json(*r.solve);
  return j;
}

namespace {

/// Time spent in each part of the evolution, for the summary (where the time goes).
struct Timings {
  double sampling = 0, velocity = 0, rows = 0, solve = 0, data_fit = 0;
  double forming = 0;  ///< the part of `solve` forming the normal equations (solvers that report it)
  nlohmann::json json() const {
    return {{"zero_set_sampling", sampling}, {"velocity", velocity}, {"rows", rows}, {"solve", solve},
            {"solve_normal_equations", forming}, {"data_fit", data_fit}};
  }
};

/// The velocity at every zero-set point, and the distance d(x_j) to the data there. With `support`
/// (velocities that want it), stalled points are tested for support and asked again.
std::vector<double> speeds(const ZeroSetSamples& samples, const DataDistance& data, const Velocity& velocity,
                           double curvature_clamp, std::vector<double>& distance, const TSpline& f,
                           const SupportData* support, int& unsupported) {
  const long n = long(samples.surface.size());
  std::vector<double> v(n);
  distance.resize(n);
  long count = 0;
#pragma omp parallel for schedule(dynamic, 64) reduction(+ : count)
  for (long j = 0; j < n; ++j) {
    const SurfacePoint& p = samples.surface[j];
    VelocitySample s;
    s.position = p.position;
    s.normal = p.gradient.normalized();
    const double limit = curvature_clamp / p.cell_size;
    s.curvature = std::clamp(mean_curvature(p.gradient, p.hessian), -limit, limit);
    const NearestData nearest = data.nearest(p.position);
    s.distance = distance[j] = nearest.distance;
    s.distance_gradient = nearest.direction;
    s.cell_size = p.cell_size;
    v[j] = velocity.speed(s);
    if (support && v[j] > -kStalledSpeed && spans_empty_space(f, *support, p.position, s.normal, nearest)) {
      s.unsupported = true;
      s.spacing = support->spacing_at(nearest.index);
      v[j] = velocity.speed(s);
      count += 1;
    }
  }
  unsupported = int(count);
  return v;
}

}  // namespace

LevelSetResult evolve_level_set(const TSpline& initial, const std::vector<Vec3>& points,
                                const EvolutionOptions& options_in,
                                const std::function<bool(const Vec3&)>& between_pieces, const ThinWalls& walls) {
  EvolutionOptions options = options_in;  // to_json() of the record visits its fields, which takes a mutable struct
  options.check();
  if (points.empty()) throw AlgorithmError("level-set evolution: no data points");
  Stopwatch clock;
  Timings timings;
  const Velocity& velocity = options.velocity_plugin();
  // The stage's own solver (stateful: it may cache a factorisation between the steps).
  const std::unique_ptr<LevelSetSolver> solver_instance = level_set_solvers().create(options.solver, "solver");
  LevelSetSolver& solver = *solver_instance;
  const TSplineBasis& basis = initial.basis();
  const Octree& tmesh = basis.octree();

  ZeroSetSampling sampling;
  sampling.subdivision = options.subdivision;
  sampling.band_subdivision = options.band_subdivision;
  sampling.band_width = options.band_width;
  sampling.hessians = true;

  const std::vector<double> floors = sign_floors(basis, options.sign_guard);
  std::vector<char> held_outside;  // hold_outside (sign_guard.hpp)
  if (between_pieces) {
    held_outside.resize(std::size_t(basis.size()));
    for (int i = 0; i < basis.size(); ++i) held_outside[std::size_t(i)] = between_pieces(basis.greville(i));
  }
  const DataDistance data(points);
  std::optional<SupportData> support;
  if (velocity.wants_support()) support.emplace(data, points);
  TSpline f = initial;
  std::vector<double> best = f.coefficients();
  std::vector<double> last_update(basis.size(), 0.0);
  double best_distance = std::numeric_limits<double>::infinity(), reference = best_distance;
  double previous_progress = 0.0;
  int best_iteration = 0, stalled = 0;
  std::vector<IterationRecord> history;
  std::string stop_reason;

  std::vector<std::vector<double>> iterates;  // for `midway`: small (coarse T-mesh, tens of steps)
  // The band's gradient rows at the sub-cell centres, computed once per site (recomputing them step
  // after step is 70 % of the rows' time).
  const int b = std::max(1, options.band_subdivision);
  GradientCache gradients(basis, tmesh.leaf_count() * b * b * b);
  for (int it = 0;; ++it) {
    iterates.push_back(f.coefficients());
    IterationRecord record;
    record.iteration = it;
    Stopwatch part;
    const DataFit fit = data_fit(f, points);
    timings.data_fit += part.seconds();
    record.mean_distance = fit.mean;
    record.max_distance = fit.max;

    part.restart();
    const ZeroSetSamples samples = sample_zero_set(f, tmesh, sampling);
    timings.sampling += part.seconds();
    record.surface_points = int(samples.surface.size());
    record.band_points = int(samples.band.size());
    if (samples.surface.empty()) {
      // The inside region has vanished (data with no volume to wrap, e.g. all on a plane or a line).
      stop_reason = "level set vanished";
      record.seconds = clock.seconds();
      history.push_back(record);
      break;
    }
    part.restart();
    std::vector<double> surface_distance;
    const std::vector<double> v = speeds(samples, data, velocity, options.curvature_clamp, surface_distance, f,
                                         support ? &*support : nullptr, record.unsupported_points);
    timings.velocity += part.seconds();
    double sum_speed = 0.0, max_speed = 0.0, min_ratio = std::numeric_limits<double>::infinity();
    record.min_gradient = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < v.size(); ++j) {
      const double s = std::abs(v[j]);
      sum_speed += s;
      max_speed = std::max(max_speed, s);
      if (s > 0.0) min_ratio = std::min(min_ratio, samples.surface[j].cell_size / s);
      const double g = samples.surface[j].gradient.norm();
      record.min_gradient = std::min(record.min_gradient, g);
      record.max_gradient = std::max(record.max_gradient, g);
    }
    record.mean_speed = sum_speed / double(v.size());
    double sum_distance = 0.0;
    for (double d : surface_distance) sum_distance += d;
    record.mean_surface_distance = sum_distance / double(v.size());
    // Progress: a chamfer distance, data to level set plus level set to data. The second half sees
    // what the first cannot: a membrane still spanning a hole of the data (a torus not yet open), a
    // neck between two components not yet pinched off.
    const double progress = fit.mean + record.mean_surface_distance;
    record.max_speed = max_speed;

    // Stopping rule (docs/design.md §1): at rest, or the distance between data and level set no longer
    // decreasing, or the cap. The iterate kept is the one closest to the data: `distance` never comes
    // to rest and `geodesic` jitters about the data, so the last iterate is not always the best.
    if (progress < best_distance) {
      best_distance = progress;
      best = f.coefficients();
      best_iteration = it;
    }
    // Stalling is judged on the mean of the last two values: `geodesic` jitters with period two about
    // the data (docs/design.md §1) while a membrane elsewhere may still be moving (a torus hole opening).
    const double smoothed = 0.5 * (progress + (it > 0 ? previous_progress : progress));
    previous_progress = progress;
    if (smoothed < reference * (1.0 - options.distance_tolerance)) {
      reference = smoothed;
      stalled = 0;
    } else {
      ++stalled;
    }
    if (record.mean_speed < options.velocity_tolerance) stop_reason = "at rest";
    else if (stalled >= options.patience) stop_reason = "distance stalled";
    else if (smoothed > reference * (1.0 + kDistanceRise)) stop_reason = "distance rising";
    else if (it >= options.max_iterations) stop_reason = "iteration cap";
    if (!stop_reason.empty()) {
      record.seconds = clock.seconds();
      history.push_back(record);
      break;
    }

    // CFL step, in each sample's own leaf: dt = cfl min_j h_j / |v_j| (big steps through coarse empty space).
    double dt = options.max_time_step;
    if (max_speed > 0.0) dt = std::min(dt, options.cfl * min_ratio);
    record.time_step = dt;

    // Least-squares rows for c'.
    part.restart();
    LeastSquaresBuilder rows(basis);
    const int velocity_rows = int(samples.surface.size());
    {
      std::vector<Vec3> x(samples.surface.size());
      std::vector<double> target(samples.surface.size());
      for (std::size_t j = 0; j < x.size(); ++j) {
        x[j] = samples.surface[j].position;
        target[j] = -v[j] * samples.surface[j].gradient.norm();  // f'(x_j) = -v |grad f|
      }
      rows.add_value_rows(x, target, 1.0);
      // Thin walls keep their inside (thin_walls.hpp): one row per wall point whose middle rose above its
      // depth, each weighted as one zero-set row (the kind's weight is spread over its rows). Value rows
      // like the velocity's, so the controls they touch count as at the surface for guard_signs.
      const WallRows held = wall_rows(walls, f, dt);
      record.held_walls = int(held.position.size());
      if (!held.position.empty())
        rows.add_value_rows(held.position, held.target, double(held.position.size()) / double(x.size()));
    }
    if (options.w_distance > 0.0) {
      std::vector<Vec3> direction(samples.band.size());
      std::vector<double> target(samples.band.size());
      for (std::size_t m = 0; m < direction.size(); ++m) {
        direction[m] = 2.0 * dt * samples.band_gradient[m];  // 2 dt grad f . grad f' = 1 - |grad f|^2
        target[m] = 1.0 - samples.band_gradient[m].squaredNorm();
      }
      rows.add_gradient_rows(samples.band, direction, target, options.w_distance, samples.band_site, gradients);
    }
    const LeastSquaresSystem system = rows.finish(options.w_smooth);
    timings.rows += part.seconds();
    record.unknowns = system.unknowns;

    part.restart();
    Eigen::VectorXd update = system.restrict(last_update);  // warm start: the previous c'
    record.solve = solver.solve(system, update);
    timings.solve += part.seconds();
    if (record.solve->details.contains("normal_equations_seconds"))
      timings.forming += record.solve->details["normal_equations_seconds"].get<double>();

    {
      // How much of the prescribed motion the step realises: |A_v c' - b_v| / |b_v| over the
      // velocity rows (0: exactly; the distance-field and smoothness terms pull it away from 0).
      double r2 = 0.0, b2 = 0.0;
      for (int r = 0; r < velocity_rows; ++r) {
        double a = -system.rhs[r];
        for (int e = system.row_begin[r]; e < system.row_begin[r + 1]; ++e) a += system.value[e] * update[system.column[e]];
        r2 += a * a;
        b2 += system.rhs[r] * system.rhs[r];
      }
      record.velocity_residual = b2 > 0.0 ? std::sqrt(r2 / b2) : 0.0;
    }
    // Explicit Euler step c <- c + dt c', guarded against nucleation away from the front.
    std::vector<double>& c = f.coefficients();
    const std::vector<double> before = c;
    std::fill(last_update.begin(), last_update.end(), 0.0);
    for (int k = 0; k < system.unknowns; ++k) {
      c[system.control[k]] += dt * update[k];
      last_update[system.control[k]] = update[k];
    }
    if (options.sign_guard > 0.0) record.guarded = guard_signs(system, system.value_rows, floors, before, c);
    if (!held_outside.empty()) record.guarded += hold_outside(held_outside, floors, before, c);
    record.seconds = clock.seconds();
    history.push_back(record);
  }
  const double evolution_seconds = clock.seconds();

  TSpline evolved(initial.shared_basis(), best);
  std::optional<RefinementReport> refinement;
  std::vector<double> transferred;
  TSpline result = evolved;
  if (options.final_refinement) {
    RefinedLevelSet refined = refine_level_set(evolved, points, options.refinement, solver);
    result = std::move(refined.level_set);
    refinement = std::move(refined.report);
    transferred = std::move(refined.transferred);
  }

  nlohmann::json summary;
  summary["velocity"] = options.velocity;
  summary["solver"] = options.solver;
  summary["options"] = to_json(options);
  summary["points"] = points.size();
  summary["tmesh"] = {{"control_points", basis.size()},
                      {"leaves", tmesh.leaf_count()},
                      {"finest_level", tmesh.finest_leaf_level()},
                      {"max_depth", tmesh.max_depth()}};
  summary["iterations"] = int(history.size()) - 1;
  summary["best_iteration"] = best_iteration;
  summary["stop_reason"] = stop_reason;
  summary["mean_distance"] = history[best_iteration].mean_distance;
  summary["max_distance"] = history[best_iteration].max_distance;
  summary["evolution_seconds"] = evolution_seconds;
  summary["evolution_timings"] = timings.json();
  if (refinement) summary["final_refinement"] = to_json(*refinement);
  summary["seconds"] = clock.seconds();

  LevelSetResult out{std::move(result), std::move(evolved), std::move(history), best_iteration,
                     std::move(stop_reason), std::move(refinement), std::move(transferred), std::move(summary),
                     std::nullopt};
  out.midway = TSpline(initial.shared_basis(), iterates[best_iteration / 2]);
  return out;
}

std::vector<Vec3> level_set_data(const std::vector<Vec3>& points, const EvolutionOptions& options) {
  for (std::size_t k = 0; k < points.size(); ++k)
    if (!points[k].allFinite()) throw AlgorithmError("level-set stage: point " + std::to_string(k) + " is not finite");
  const double cell = 2.0 * (1.0 + options.tmesh.margin) / double(1 << options.tmesh.max_depth);
  return thin_points(points, std::size_t(options.max_points), cell);
}

namespace {
// With a carve or wrap start, the T-mesh is refined toward the data while its cells stay at least this
// many median data spacings wide.
constexpr double kFinestCellSpacings = 0.5;
}  // namespace

LevelSetResult compute_level_set(const std::vector<Vec3>& all_points, const EvolutionOptions& options) {
  options.check();
  Stopwatch clock;
  const std::vector<Vec3> points = level_set_data(all_points, options);
  auto basis = std::make_shared<TSplineBasis>(build_octree(points, options.tmesh));
  const double tmesh_seconds = clock.seconds();
  EvolutionOptions stage = options;
  stage.final_refinement = false;
  const auto use_round_settings = [&] {
    stage.max_iterations = options.fine.max_iterations;
    if (options.fine.w_distance >= 0.0) stage.w_distance = options.fine.w_distance;
    if (!options.fine_velocity.empty()) stage.use_velocity(options.fine_velocity, options.fine_velocity_plugin());
  };
  nlohmann::json initial_summary;  // the record of the carving or wrap: TL summary "initial"
  std::unique_ptr<DataCarving> carving;
  const TSpline initial = [&] {
    if (options.initial == "sphere")
      return initial_level_set(basis, points, options.initial_radius_factor, options.initial_box_margin);
    // data_wrap.hpp, data_carving.hpp: the data decide the topology, so the T-mesh is refined toward the data
    // to its finest level before the evolution (a coarse T-mesh would blur the holes and gaps shut), and the
    // one evolution starts near the data, as a coarse-to-fine round does.
    Stopwatch part;  // where the start's time goes: TL summary initial.timings
    nlohmann::json timings;
    std::function<double(const Vec3&)> distance;
    std::unique_ptr<DataWrap> wrap;
    std::vector<std::unique_ptr<DataWrap>> piece_wraps;  // carve: the wrap of each piece of the data
    if (options.initial == "wrap") {
      wrap = std::make_unique<DataWrap>(points, options.wrap_alpha, kWrapOffsetSpacings);
      distance = [&wrap](const Vec3& x) { return (*wrap)(x); };
      const WrapSummary& w = wrap->summary();
      initial_summary = {{"method", "wrap"}, {"spacing", w.spacing}, {"alpha", w.alpha},   {"offset", w.offset},
                      {"faces", w.faces}, {"genus", w.genus},     {"components", w.components}, {"seconds", w.seconds}};
    } else {
      carving = std::make_unique<DataCarving>(points, options.wrap_alpha);
      // One wrap per piece of the data (data_pieces.hpp): a wrap of all the data would join two pieces
      // across the gap the carving opened between them. A piece too small or flat to wrap has the carving only.
      const int pieces = carving->summary().data_pieces;
      if (pieces == 1) {  // as the wrap start: a wrap that fails is an error
        piece_wraps.push_back(std::make_unique<DataWrap>(points, options.wrap_alpha, kWrapOffsetSpacings));
      } else {
        for (const std::vector<Vec3>& piece : points_by_piece(points, carving->pieces())) {
          try {
            piece_wraps.push_back(std::make_unique<DataWrap>(piece, options.wrap_alpha, kWrapOffsetSpacings));
          } catch (const AlgorithmError&) {
            piece_wraps.push_back(nullptr);
          }
        }
      }
      distance = [&carving, &piece_wraps](const Vec3& x) {
        const CarvingValue c = carving->evaluate(x);
        const DataWrap* piece_wrap = piece_wraps[std::size_t(c.piece)].get();
        return piece_wrap ? std::min(c.distance, (*piece_wrap)(x)) : c.distance;
      };
      const CarvingSummary& c = carving->summary();
      initial_summary = {{"method", "carve"}, {"spacing", c.spacing}, {"alpha_spacings", c.alpha},
                         {"inside_cells", c.inside_cells}, {"boundary_facets", c.boundary_facets},
                         {"data_pieces", c.data_pieces}, {"reopened_cells", c.reopened_cells}, {"seconds", c.seconds}};
    }
    timings["carving_and_wraps"] = part.seconds();
    part.restart();
    // enclosed_volume.hpp: data that bound no volume at the ball's scale (an open cut) start from the sphere.
    const std::vector<double> local_spacing =
        carving ? carving->local_spacing() : DataDistance(points).local_spacing(kSpacingNeighbours);
    const EnclosureCheck enclosure =
        check_enclosure(points, local_spacing, initial_summary.at("spacing").get<double>(), distance);
    initial_summary["unenclosed_fraction"] = enclosure.fraction();
    timings["enclosure"] = part.seconds();
    part.restart();
    if (enclosure.fraction() > kMaxUnenclosedFraction) {
      initial_summary["timings"] = timings;
      initial_summary["fallback"] = "sphere";
      return initial_level_set(basis, points, options.initial_radius_factor, options.initial_box_margin);
    }
    TSpline f = initial_level_set(basis, points, distance);
    // One split per level from the octree's finest leaf to max_depth, near the data: where the octree
    // already reached max_depth somewhere, nothing is split. Splitting every leaf near the data down to
    // max_depth instead cost 2.1x the dev half's time for one input's topology (docs/design.md §8).
    // Cells finer than half the data's spacing would have no data of their own to fit.
    const double spacing = initial_summary.at("spacing").get<double>();
    const auto cell_side = [&f](int level) { return f.tmesh().side() / double(1 << level); };
    for (int level = f.tmesh().finest_leaf_level() + 1;
         level <= options.tmesh.max_depth && cell_side(level) >= kFinestCellSpacings * spacing; ++level) {
      TSpline refined = refine_toward_data(f, points, level, options.fine);
      if (refined.shared_basis() == f.shared_basis()) break;
      f = initial_level_set(refined.shared_basis(), points, distance);
    }
    timings["refinement_and_fit"] = part.seconds();  // the start's coefficients on each refined T-mesh
    // gap_refinement.hpp: a gap between pieces narrower than two cells gets cells one level finer.
    if (carving && carving->summary().data_pieces > 1) {
      GapRefinement gaps;
      Octree refined = refine_narrow_gaps(f.tmesh(), points, carving->pieces(), &gaps);
      initial_summary["narrow_gaps"] = {{"pairs", gaps.narrow_pairs}, {"split_leaves", gaps.split_leaves},
                                        {"level", gaps.level}, {"seconds", gaps.seconds}};
      if (gaps.split_leaves > 0)
        f = initial_level_set(std::make_shared<TSplineBasis>(std::move(refined)), points, distance);
    }
    initial_summary["timings"] = timings;
    use_round_settings();
    return f;
  }();
  // The gaps the carving opened between separate pieces of the data stay open (hold_outside, sign_guard.hpp).
  std::function<bool(const Vec3&)> between_pieces;
  if (carving && carving->summary().data_pieces > 1)
    between_pieces = [&carving](const Vec3& x) { return carving->reopened(x); };
  // The walls of the data as the start orients them (thin_walls.hpp); not from the sphere, which says
  // nothing of the data's faces.
  ThinWalls walls;
  if (options.initial != "sphere" && !initial_summary.contains("fallback")) {
    Stopwatch part;
    walls = thin_walls(points, DataDistance(points), initial, initial.tmesh());
    initial_summary["thin_walls"] = walls.size();
    initial_summary["timings"]["thin_walls"] = part.seconds();
  }
  LevelSetResult result = evolve_level_set(initial, points, stage, between_pieces, walls);

  // Coarse-to-fine rounds (coarse_to_fine.hpp): refine near the data, evolve again from there.
  nlohmann::json rounds = nlohmann::json::array();
  const auto record_round = [&](const LevelSetResult& r, int round) {
    // The solver's share of the round (CG iterations grow with the T-mesh: where the time goes).
    long solver_iterations = 0;
    int unknowns = 0;
    double solve_seconds = 0.0;
    for (const IterationRecord& step : r.history) {
      if (step.round != round) continue;
      unknowns = std::max(unknowns, step.unknowns);
      if (!step.solve) continue;
      solver_iterations += step.solve->iterations;
      solve_seconds += step.solve->seconds;
    }
    rounds.push_back({{"round", round},
                      {"velocity", stage.velocity},
                      {"unknowns", unknowns},
                      {"solver_iterations", solver_iterations},
                      {"solve_seconds", solve_seconds},
                      {"control_points", r.evolved.basis().size()},
                      {"finest_level", r.evolved.tmesh().finest_leaf_level()},
                      {"iterations", r.summary["iterations"]},
                      {"stop_reason", r.stop_reason},
                      {"mean_distance", r.summary["mean_distance"]},
                      {"seconds", r.summary["evolution_seconds"]}});
  };
  // A later evolution's history continues the earlier one's (iterations, seconds, timings).
  const auto append = [&result](LevelSetResult next, int round) {
    const int offset = result.history.back().iteration + 1;
    for (IterationRecord& r : next.history) {
      r.iteration += offset;
      r.round = round;
      r.seconds += result.history.back().seconds;
    }
    for (auto& [key, value] : next.summary["evolution_timings"].items())
      value = value.get<double>() + result.summary["evolution_timings"][key].get<double>();
    next.best_iteration += int(result.history.size());
    next.history.insert(next.history.begin(), result.history.begin(), result.history.end());
    next.midway = std::move(result.midway);
    result = std::move(next);
  };
  record_round(result, 0);
  use_round_settings();
  for (int round = 1; round <= options.fine.levels; ++round) {
    const int level = result.evolved.tmesh().finest_leaf_level() + 1;
    if (level > options.tmesh.max_depth) break;
    TSpline refined = refine_toward_data(result.evolved, points, level, options.fine);
    if (refined.shared_basis() == result.evolved.shared_basis()) break;  // nothing left to split
    append(evolve_level_set(refined, points, stage, {}, walls), round);
    record_round(result, round);
  }

  if (options.final_refinement) {
    const std::unique_ptr<LevelSetSolver> solver = level_set_solvers().create(options.solver, "solver");
    RefinedLevelSet refined = refine_level_set(result.evolved, points, options.refinement, *solver);
    result.level_set = std::move(refined.level_set);
    result.transferred = std::move(refined.transferred);
    result.summary["final_refinement"] = to_json(refined.report);
    result.refinement = std::move(refined.report);
  }
  EvolutionOptions given = options;  // the options as given: the stage's were the rounds' (fine velocity)
  result.summary["options"] = to_json(given);
  result.summary["tmesh"] = {{"control_points", result.level_set.basis().size()},
                             {"leaves", result.level_set.tmesh().leaf_count()},
                             {"finest_level", result.level_set.tmesh().finest_leaf_level()},
                             {"max_depth", result.level_set.tmesh().max_depth()},
                             {"initial_control_points", basis->size()},
                             {"initial_finest_level", basis->octree().finest_leaf_level()}};
  result.summary["rounds"] = std::move(rounds);
  if (!initial_summary.is_null()) result.summary["initial"] = std::move(initial_summary);
  result.summary["iterations"] = int(result.history.size()) - 1;
  result.summary["best_iteration"] = result.best_iteration;
  result.summary["evolution_seconds"] = result.history.back().seconds;
  result.summary["tmesh_seconds"] = tmesh_seconds;
  result.summary["points"] = all_points.size();
  result.summary["points_used"] = points.size();
  result.summary["seconds"] = clock.seconds();
  return result;
}

}  // namespace dtsl
