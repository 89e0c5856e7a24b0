// Phase 3 of the method (paper §4, docs/design.md §4): the data-driven bilateral evolution that recovers
// sharp features of the displaced mesh.
//
// Each iteration: foot points q_k of all data on the current mesh (Fig. 2 cases, Eq. 6) and its sharp
// vertices (sharp_vertices.hpp, detected anew on every iteration's mesh); minimise
//   F(V') = E_dist + w E_bila                                                             (Eq. 4)
//   E_dist = sum_k |q_k + sum_{j in phi(p_k)} lambda_j v'_j - p_k|^2                        (Eq. 5, 6)
//   E_bila = sum_i |v_i + v'_i - v'_i target|^2, the target from the bilateral filter      (Eq. 7, 8)
// over the velocities v'_i of the sharp vertices only (all others v' = 0, paper §4.2), so E_dist keeps
// just the data whose foot points depend on a sharp vertex and E_bila just the sharp vertices. The
// problem is linear least squares; its x, y and z parts decouple (sharpen_solver.hpp). An explicit
// Euler step V <- V + dtau V' follows (halved while it would flip a triangle). The loop stops when e_avr
// (Eq. 9, all data) no longer falls, or has fallen by less than min_relative_decrease in `patience`
// iterations in a row (that last step is not taken), or after max_iterations. Degenerate triangles are then
// removed (degenerate_removal.hpp).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "algorithms/sharpen/degenerate_removal.hpp"
#include "algorithms/sharpen/sharp_vertices.hpp"
#include "framework/config/options.hpp"
#include "framework/core/types.hpp"

namespace dtsl::sharpen {

struct BilateralEvolutionOptions final : Options {
  /// Marching step length delta_t of the initial mesh (paper §2.2); the filter widths derive from it.
  double delta = 0.03;
  /// sigma_c = sigma_s = sigma_factor x delta (paper §4.3: 2 delta_t).
  double sigma_factor = 2.0;
  /// N(v) of Eq. 8: triangles with their centroid within support_factor x sigma_c of v.
  double support_factor = 2.0;
  /// w of Eq. 4: weight of the bilateral energy against the data energy.
  double bilateral_weight = 1.0;
  /// dtau of the explicit Euler step V <- V + dtau V'.
  double time_step = 1.0;
  /// Iteration cap (the paper: usually within 10 iterations).
  int max_iterations = 20;
  /// An iteration whose e_avr falls by less than this fraction is a slow one.
  double min_relative_decrease = 1e-3;
  /// Stop at the patience-th slow iteration in a row (that step is not taken; the slow ones before it
  /// are, as each still lowers e_avr). 1: stop at the first. A step that raises e_avr always stops.
  /// 2 (ours): corners may go on converging after a slow step (docs/experiments.md, "The bilateral
  /// evolution's stop").
  int patience = 2;
  /// Foot-point case of Fig. 2: barycentric coordinates below this count as zero.
  double snap = 1e-6;
  /// Solver plugin of the linear least-squares problem: eigen_ldlt or ceres.
  std::string solver = "eigen_ldlt";
  SharpVertexOptions sharp;
  DegenerateRemovalOptions degenerate;

  void visit(FieldVisitor& v) override;
  void check() const override;
};

/// The stopping rule of the evolution's loop (paper §4: until e_avr no longer decreases), with a threshold
/// and a patience. Fed each iteration's e_avr against the best so far, it says whether to take the step
/// or to stop (and then why: "rose" when e_avr did not fall, "slow" at the patience-th iteration in a
/// row that lowered it by less than min_relative_decrease). Patience 1 stops at the first slow one.
class StoppingRule {
 public:
  StoppingRule(double min_relative_decrease, int patience) : threshold_(min_relative_decrease), patience_(patience) {}
  /// "" to take the step; else the reason to stop without it ("rose" or "slow"; NaN counts as a rise).
  std::string judge(double e, double best_e);
  int slow_in_a_row() const { return slow_in_a_row_; }

 private:
  double threshold_;
  int patience_;
  int slow_in_a_row_ = 0;
};

struct BilateralEvolutionResult {
  TriangleMesh mesh;               ///< the sharpened mesh (vertex normals recomputed if the input had them)
  std::vector<int> sharp_vertices; ///< vertices of `mesh` that moved (sharp at some accepted iteration)
  std::vector<int> face_origin;    ///< for each face of `mesh`, its index in the input mesh
  nlohmann::json summary;          ///< counts, e_avr per iteration, time
};

/// Throws AlgorithmError for no data, a non-finite point or vertex, a mesh without faces or with an
/// index out of range; ConfigError (naming the field) for invalid options or an unknown solver.
BilateralEvolutionResult bilateral_evolution(const TriangleMesh& mesh, const std::vector<Vec3>& points,
                                             const BilateralEvolutionOptions& options);

}  // namespace dtsl::sharpen
