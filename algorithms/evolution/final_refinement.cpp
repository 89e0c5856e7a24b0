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
  check_positive("outlier_cells", outlier_cells);
  check_range("subdivision", subdivision, 1, 4);
  check_range("band_subdivision", band_subdivision, 1, 4);
  check_range("band_width", band_width, 0.5, 10.0);
  check_range("sign_guard", sign_guard, 0.0, 10.0);
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
                  ? transfer_level_set(level_set, std::move(tree), &report.transfer)
                  : level_set;
  const std::shared_ptr<const TSplineBasis> basis = f.shared_basis();
  report.control_points_after = basis->size();
  const std::vector<double> transferred = f.coefficients();

  // 3. Gauss-Newton steps of the direct fit.
  const Octree& mesh = basis->octree();
  const std::vector<double> floors = options.sign_guard > 0.0 ? sign_floors(*basis, options.sign_guard) : std::vector<double>();
  // A focused refinement (refine-on-flip) fits only the control points its refinement changed: f is
  // the accepted one everywhere else, and a global refit would move the zero set far from the flips.
  const std::vector<char>* free = !focus.empty() && report.rounds > 0 ? &report.transfer.changed_flags : nullptr;
  for (int it = 0; it < options.fit_iterations; ++it) {
    LeastSquaresBuilder rows(*basis);
    // Data rows: f(p_k) + sum_i R_i(p_k) delta_i = 0, for the points near the level set.
    std::vector<Vec3> fitted;
    std::vector<double> target;
    fitted.reserve(points.size());
    for (const Vec3& p : points) {
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
    // Distance-field rows: 2 grad f(y) . grad delta(y) = 1 - |grad f(y)|^2 on the band.
    const ZeroSetSamples samples = sample_zero_set(f, mesh, sampling);
    if (options.w_distance > 0.0 && !samples.band.empty()) {
      std::vector<Vec3> direction;
      std::vector<double> rhs;
      for (const Vec3& g : samples.band_gradient) {
        direction.push_back(2.0 * g);
        rhs.push_back(1.0 - g.squaredNorm());
      }
      rows.add_gradient_rows(samples.band, direction, rhs, options.w_distance);
    }
    if (free && rows.rows_touching(*free) == 0) break;  // no data or band near the changed part
    const LeastSquaresSystem system = rows.finish(options.w_smooth, free);
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
