// The final refinement of the level set ([55], docs/design.md §1 end; paper §2.1: "that paper also
// discusses a 'final refinement' step, which can be used to improve the result, especially for noisy
// data", and §3.2: "find a better base surface by using more degrees of freedom ... and applying the
// 'final refinement' step"):
//
//  1. refine the T-mesh where the zero set crosses leaves near the data (or near given focus points,
//     e.g. where Phase 2's displacement flipped triangles) down to a target level;
//  2. transfer f to the refined T-mesh: control points whose knot vectors did not change keep their
//     coefficient (f is unchanged where only they are active), the new or changed ones take the old
//     f at their Greville point (quasi-interpolation);
//  3. fit directly, by Gauss–Newton steps delta on the coefficients starting from the transferred ones:
//        sum_k f(p_k)^2 / K  +  w_D sum_m (|grad f(y_m)|^2 - 1)^2 / M  +  w_S |delta|^2 / n ,
//     the distance-field term linearised as in the evolution (2 grad f . grad delta), so each step is
//     the same kind of least-squares system the evolution's solvers already solve. Data points
//     farther than outlier_cells leaf sides from the level set are left out of the fit (outliers,
//     or data the evolution did not reach: they would drag the surface across the cell).
// Holes in the data keep their coarse cells and get no data rows: the fill stays smooth. With focus
// points (D-Map's refine-on-flip rounds), step 1 refines only near them and step 3 fits only the
// control points the refinement changed (new, or with new knots), holding the rest of f: the zero set
// away from the flips stays where the accepted level set has it.
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "algorithms/evolution/data_fit.hpp"
#include "algorithms/evolution/level_set_transfer.hpp"
#include "algorithms/evolution/solver.hpp"
#include "algorithms/tspline/tspline.hpp"
#include "framework/config/options.hpp"

namespace dtsl {

struct FinalRefinementOptions final : Options {
  int target_level = -1;
  double data_reach = 1.0;
  int fit_iterations = 1;
  double w_distance = 0.3;
  double w_smooth = 1e-3;
  double outlier_cells = 2.0;
  int subdivision = 2;
  int band_subdivision = 2;
  double band_width = 2.0;
  double sign_guard = 0.25;

  void visit(FieldVisitor& v) override {
    v.field("target_level", target_level,
            "refine surface cells near data to this octree level; -1 = the finest level the T-mesh already "
            "has (capped at its max_depth)");
    v.field("data_reach", data_reach,
            "a leaf the zero set crosses is refined if a data point lies within data_reach x its side of the "
            "surface in it");
    v.field("fit_iterations", fit_iterations,
            "Gauss-Newton steps of the direct fit (0: refine and transfer only; why 1: docs/design.md §8)");
    v.field("w_distance", w_distance,
            "weight w_D of the distance-field term |grad f|^2 = 1 (0.3, ours: the evolution's 1 holds the surface "
            "at the evolved shape, less opens spurious handles: docs/design.md §8)");
    v.field("w_smooth", w_smooth, "weight w_S of the smoothness of each Gauss-Newton step");
    v.field("outlier_cells", outlier_cells,
            "data points farther than this many leaf sides from the level set are left out of the fit");
    v.field("subdivision", subdivision, "zero-set samples (which leaves to refine): centres of s^3 sub-cells per leaf");
    v.field("band_subdivision", band_subdivision, "distance-field band samples: centres of b^3 sub-cells per leaf");
    v.field("band_width", band_width, "distance-field band: |f| / |grad f| < band_width x leaf side");
    v.field("sign_guard", sign_guard,
            "no nucleation (sign_guard.hpp): a coefficient no data row touches keeps its sign, at least this "
            "fraction of its cell size from zero; 0 disables");
  }
  void check() const override;
};

struct RefinementReport {
  int rounds = 0;                  ///< octree refinement rounds (one level each)
  int leaves_split = 0;
  int control_points_before = 0, control_points_after = 0;
  int target_level = 0;
  int fitted_points = 0;           ///< data points in the fit (outliers left out)
  int guarded = 0;                 ///< coefficients the no-nucleation guard held
  DataFit before, after;           ///< data-to-level-set distance before refinement and after the fit
  std::vector<SolveReport> solves;
  TransferReport transfer;         ///< how f reached the refined T-mesh (rounds > 0)
  double seconds = 0.0;
};
nlohmann::json to_json(const RefinementReport& r);

struct RefinedLevelSet {
  TSpline level_set;
  RefinementReport report;
  /// Coefficients of the input f transferred onto the refined T-mesh, before the fit (same basis as
  /// level_set): the fit is level_set - transferred (refinement_guard.hpp scales it back).
  std::vector<double> transferred;
};

/// What refine_level_set does when no leaf is to be split: fit on the T-mesh as it is (the final
/// refinement: the fit still helps), or return the input unchanged with report.rounds == 0 (a caller
/// that wants refinement only, like the flip fallback of D-Map, saves the fit it would discard).
enum class WhenNothingToSplit { fit, skip_fit };

/// Refines `level_set` near `points` (or, if `focus` is not empty, only where the zero set passes
/// within data_reach leaf sides of a focus point) and fits it to `points`. ConfigError for invalid
/// options; AlgorithmError for no points or a solver failure.
RefinedLevelSet refine_level_set(const TSpline& level_set, const std::vector<Vec3>& points,
                                 const FinalRefinementOptions& options, LevelSetSolver& solver,
                                 const std::vector<Vec3>& focus = {},
                                 WhenNothingToSplit unsplit = WhenNothingToSplit::fit);

}  // namespace dtsl
