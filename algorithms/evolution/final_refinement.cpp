#include "algorithms/evolution/final_refinement.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "algorithms/evolution/data_distance.hpp"
#include "algorithms/evolution/least_squares_rows.hpp"
#include "algorithms/evolution/level_set_transfer.hpp"
#include "algorithms/evolution/sign_guard.hpp"
#include "algorithms/evolution/zero_set.hpp"
#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"

namespace dtsl {

void FinalRefinementOptions::check() const {
  check_range("target_level", target_level, -1, kMaxOctreeDepth);
  check_range("data_reach", data_reach, 0.0, 100.0);
  check_range("fit_iterations", fit_iterations, 0, 100);
  check_non_negative("w_distance", w_distance);
  check_non_negative("w_smooth", w_smooth);
  check_one_of("smoothness", smoothness, {"tikhonov", "first_order"});
  check_positive("outlier_cells", outlier_cells);
  check_range("subdivision", subdivision, 1, 4);
  check_range("band_subdivision", band_subdivision, 1, 4);
  check_range("band_width", band_width, 0.5, 10.0);
  check_range("sign_guard", sign_guard, 0.0, 10.0);
  check_one_of("transfer", transfer, {"quasi_interpolation", "least_squares"});
}

nlohmann::json to_json(const RefinementReport& r) {
  nlohmann::json solves = nlohmann::json::array();
  for (const SolveReport& s : r.solves) solves.push_back(to_json(s));
  nlohmann::json j = {{"rounds", r.rounds},
          {"leaves_split", r.leaves_split},
          {"control_points_before", r.control_points_before},
          {"control_points_after", r.control_points_after},
          {"target_level", r.target_level},
          {"fitted_points", r.fitted_points},
          {"free_control_points", r.free_control_points},
          {"guarded", r.guarded},
          {"mean_distance_before", r.before.mean},
          {"max_distance_before", r.before.max},
          {"mean_distance_after", r.after.mean},
          {"max_distance_after", r.after.max},
          {"solves", solves},
          {"seconds", r.seconds}};
  if (r.rounds > 0) j["transfer"] = to_json(r.transfer);
  return j;
}

RefinedLevelSet refine_level_set(const TSpline& level_set, const std::vector<Vec3>& points,
                                 const FinalRefinementOptions& options, LevelSetSolver& solver,
                                 const std::vector<Vec3>& focus, WhenNothingToSplit unsplit) {
  options.check();
  if (points.empty()) throw AlgorithmError("final refinement: no data points");
  Stopwatch clock;
  RefinementReport report;
  report.control_points_before = level_set.basis().size();
  report.before = data_fit(level_set, points);

  // 1. Refine, one level per round, the leaves the zero set crosses near the data (or the focus).
  const DataDistance near(focus.empty() ? points : focus);
  Octree tree = level_set.tmesh();
  report.target_level = std::min(options.target_level < 0 ? tree.finest_leaf_level() : options.target_level,
                                 tree.max_depth());
  const Balance balance = balance_of(tree);
  ZeroSetSampling sampling;
  sampling.subdivision = options.subdivision;
  sampling.band_subdivision = options.band_subdivision;
  sampling.band_width = options.band_width;
  sampling.hessians = false;
  for (;;) {
    const ZeroSetSamples samples = sample_zero_set(level_set, tree, sampling);
    std::vector<int> split;
    for (const SurfacePoint& p : samples.surface) {
      if (tree.leaf(p.leaf).level >= report.target_level) continue;
      if (near.nearest(p.position).distance <= options.data_reach * p.cell_size) split.push_back(p.leaf);
    }
    std::sort(split.begin(), split.end());
    split.erase(std::unique(split.begin(), split.end()), split.end());
    if (split.empty()) break;
    tree = refine_octree(tree, split, balance);
    report.leaves_split += int(split.size());
    ++report.rounds;
  }

  if (report.rounds == 0 && unsplit == WhenNothingToSplit::skip_fit) {
    report.after = report.before;
    report.seconds = clock.seconds();
    return {level_set, std::move(report), level_set.coefficients()};
  }

  // 2. Transfer f onto the refined T-mesh.
  TSpline f = report.rounds > 0
                  ? transfer_level_set(level_set, std::move(tree), transfer_from_string(options.transfer), &report.transfer)
                  : level_set;
  const std::shared_ptr<const TSplineBasis> basis = f.shared_basis();
  report.control_points_after = basis->size();
  const std::vector<double> transferred = f.coefficients();

  // Local fit (options.local_fit, focus given and something split; with nothing split the fit is the
  // global one, or skipped with WhenNothingToSplit::skip_fit): only the control points whose support overlaps a leaf
  // this refinement created are unknowns, and only the rows that depend on them are built. Elsewhere the
  // T-mesh, and so f (the transfer keeps unchanged knot vectors' coefficients), is what the caller had
  // already fitted; refitting it all costs a global solve per D-Map flip round.
  std::vector<char> free;
  if (options.local_fit && !focus.empty() && report.rounds > 0) {
    const Octree& old_tree = level_set.tmesh();
    free.assign(std::size_t(basis->size()), 0);
    for (int l = 0; l < basis->octree().leaf_count(); ++l) {
      const Octree::Cell& cell = basis->octree().leaf(l);
      if (old_tree.leaf(old_tree.leaf_at(cell.origin)).level >= cell.level) continue;  // not new
      for (int c : basis->support(l)) free[std::size_t(c)] = 1;
    }
    for (char c : free) report.free_control_points += c;
  }
  // A point whose leaf's support list holds no free control point adds no row (rows of a local fit).
  std::vector<char> leaf_touches_free;
  if (!free.empty()) {
    leaf_touches_free.assign(std::size_t(basis->octree().leaf_count()), 0);
    for (int l = 0; l < basis->octree().leaf_count(); ++l)
      for (int c : basis->support(l))
        if (free[std::size_t(c)]) {
          leaf_touches_free[std::size_t(l)] = 1;
          break;
        }
  }
  const auto touches_free = [&](const Vec3& x) {
    return free.empty() || leaf_touches_free[std::size_t(basis->leaf_of(x))] != 0;
  };

  // 3. Gauss-Newton steps of the direct fit.
  const Smoothness smoothness = smoothness_from_string(options.smoothness);
  std::vector<std::array<int, 2>> edges;
  if (smoothness == Smoothness::first_order && options.w_smooth > 0.0) edges = control_edges(*basis);
  const Octree& mesh = basis->octree();
  const std::vector<double> floors = options.sign_guard > 0.0 ? sign_floors(*basis, options.sign_guard) : std::vector<double>();
  for (int it = 0; it < options.fit_iterations; ++it) {
    LeastSquaresBuilder rows(*basis);
    if (!free.empty()) rows.restrict_to(free);
    // Data rows: f(p_k) + sum_i R_i(p_k) delta_i = 0, for the points near the level set.
    std::vector<Vec3> fitted;
    std::vector<double> target;
    fitted.reserve(points.size());
    for (const Vec3& p : points) {
      if (!touches_free(p)) continue;
      Vec3 g;
      const double v = f.evaluate(p, &g);
      const double side = mesh.leaf_side(mesh.locate(p));
      if (std::abs(v) > options.outlier_cells * side * g.norm()) continue;
      fitted.push_back(p);
      target.push_back(-v);
    }
    report.fitted_points = int(fitted.size());
    if (fitted.empty()) break;  // the level set is nowhere near the data: nothing to fit
    rows.add_value_rows(fitted, target, 1.0);
    // A local fit drops the rows in which no free function is active: count the data rows kept.
    if (!free.empty()) report.fitted_points = rows.rows();
    // Distance-field rows: 2 grad f(y) . grad delta(y) = 1 - |grad f(y)|^2 on the band.
    const ZeroSetSamples samples = sample_zero_set(f, mesh, sampling);
    if (options.w_distance > 0.0 && !samples.band.empty()) {
      std::vector<Vec3> band, direction;
      std::vector<double> rhs;
      for (std::size_t m = 0; m < samples.band.size(); ++m) {
        if (!touches_free(samples.band[m])) continue;
        band.push_back(samples.band[m]);
        direction.push_back(2.0 * samples.band_gradient[m]);
        rhs.push_back(1.0 - samples.band_gradient[m].squaredNorm());
      }
      rows.add_gradient_rows(band, direction, rhs, options.w_distance);
    }
    if (rows.rows() == 0) break;  // a local fit whose free functions no sample reaches
    const LeastSquaresSystem system = rows.finish(smoothness, options.w_smooth, &edges);
    Eigen::VectorXd delta = Eigen::VectorXd::Zero(system.unknowns);
    report.solves.push_back(solver.solve(system, delta));
    std::vector<double>& coefficients = f.coefficients();
    const std::vector<double> before = coefficients;
    for (int k = 0; k < system.unknowns; ++k) coefficients[system.control[k]] += delta[k];
    // No nucleation away from the data (sign_guard.hpp): the data rows mark the surface.
    if (options.sign_guard > 0.0) report.guarded += guard_signs(system, system.value_rows, floors, before, coefficients);
  }
  report.after = data_fit(f, points);
  report.seconds = clock.seconds();
  return {std::move(f), std::move(report), transferred};
}

}  // namespace dtsl
