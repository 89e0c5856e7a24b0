// The linear least-squares problems of the level-set stage, as weighted rows over T-spline
// coefficients (docs/design.md §1):
//
//   evolution step, unknowns c' (the time derivative of the coefficients):
//     value rows     f'(x_j) = -v(x_j) |grad f(x_j)|                              (follow the velocity)
//     gradient rows  2 dt grad f(y_m) . grad f'(y_m) = 1 - |grad f(y_m)|^2          (distance field)
//     smoothness     w_S |c'|^2
//   final refinement, unknowns delta (a Gauss-Newton step on the coefficients):
//     value rows     f(p_k) + delta-part = 0                                      (fit the data)
//     gradient rows  2 grad f(y_m) . grad delta-part = 1 - |grad f(y_m)|^2          (distance field)
//     smoothness     w_S |delta|^2
//
// where f' = sum_i c'_i R_i with R_i = B_i / sum_j B_j (TSplineBasis::active). Every kind of row is
// weighted by (its weight) / (number of rows of that kind), so the balance between the terms does not
// depend on how densely each is sampled (docs/design.md §1). The smoothness term (Tikhonov, R = I) is
// stored as rows too, one per unknown, so that every solver — normal equations or Ceres — sees one
// uniform problem.
//
// Only control points that some value or gradient row touches are unknowns (renumbered densely); the
// others keep a zero update, which is exact (their normal equations read w c'_i = 0).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "algorithms/tspline/tspline_basis.hpp"

namespace dtsl {

/// minimise sum_r weight_r (a_r . u - rhs_r)^2 over the unknowns u. Rows in compressed sparse row
/// form, columns in [0, unknowns), ascending within each row (LeastSquaresBuilder::finish sorts them).
struct LeastSquaresSystem {
  int unknowns = 0;
  std::vector<int> control;        ///< unknown -> control point index of the basis
  std::vector<int> row_begin{0};   ///< row r is entries [row_begin[r], row_begin[r + 1])
  std::vector<int> column;
  std::vector<double> value;
  std::vector<double> rhs, weight;
  int value_rows = 0, gradient_rows = 0, smoothness_rows = 0;  ///< rows of each kind (smoothness rows last)

  int rows() const { return int(rhs.size()); }
  std::size_t nonzeros() const { return column.size(); }

  /// sum_r weight_r (a_r . u - rhs_r)^2.
  double objective(const Eigen::VectorXd& u) const;
  /// A^T W (A u - b): the gradient of the objective / 2, zero at the minimiser.
  Eigen::VectorXd normal_residual(const Eigen::VectorXd& u) const;
  /// |A^T W (A u - b)| / |A^T W b| (0 for u = 0 and b = 0): how far u is from solving the normal
  /// equations, independent of scale. Every solver reports it, and fails above its tolerance.
  double relative_residual(const Eigen::VectorXd& u) const;

  /// The unknowns as a full coefficient vector (zero for control points that are not unknowns).
  std::vector<double> expand(const Eigen::VectorXd& u, int controls) const;
  /// The restriction of a full coefficient vector to the unknowns (a warm start).
  Eigen::VectorXd restrict(const std::vector<double>& full) const;
};

/// grad R_i at fixed sample sites of one basis, kept across calls: the evolution's band samples are the
/// centres of sub-cells of the T-mesh's leaves (zero_set.hpp), the same points step after step while the
/// band drifts, and a gradient row there differs from the last step's only by its direction. Site s is
/// any number in [0, sites); the caller keeps the numbering fixed (ZeroSetSamples::band_site).
class GradientCache {
 public:
  /// At most `max_bytes` of entries are kept (sites beyond are computed afresh each time: the same rows).
  GradientCache(const TSplineBasis& basis, int sites, std::size_t max_bytes = std::size_t(256) << 20)
      : basis_(basis), slot_(std::size_t(sites), -1), max_bytes_(max_bytes) {}
  const TSplineBasis& basis() const { return basis_; }
  /// Computes the missing sites among `sites` (negative entries: not a site, skipped) at `x`, in parallel.
  void fill(const std::vector<Vec3>& x, const std::vector<int>& sites);
  /// The active functions of a filled site: count, their control indices and grad R_i.
  int size(int site) const { return begin_[std::size_t(slot_[std::size_t(site)]) + 1] - begin_[std::size_t(slot_[std::size_t(site)])]; }
  const int* index(int site) const { return &index_[std::size_t(begin_[std::size_t(slot_[std::size_t(site)])])]; }
  const Vec3* gradient(int site) const { return &gradient_[std::size_t(begin_[std::size_t(slot_[std::size_t(site)])])]; }
  bool has(int site) const { return slot_[std::size_t(site)] >= 0; }
  std::size_t filled() const { return begin_.size() - 1; }
  std::size_t bytes() const { return index_.size() * (sizeof(int) + sizeof(Vec3)); }

 private:
  const TSplineBasis& basis_;
  std::vector<int> slot_;       // site -> slot, -1: not computed yet
  std::vector<int> begin_{0};   // slot -> its entries [begin_[slot], begin_[slot + 1])
  std::vector<int> index_;
  std::vector<Vec3> gradient_;
  std::size_t max_bytes_;
  bool full_ = false;  // an entry did not fit: fill() computes nothing more
};

/// Collects rows over the global control indices of a basis, then renumbers them (finish()).
class LeastSquaresBuilder {
 public:
  explicit LeastSquaresBuilder(const TSplineBasis& basis) : basis_(basis) {}

  /// Rows added so far.
  int rows() const { return int(rhs_.size()); }
  /// Rows added so far with an entry in a flagged control point (what finish(w, &free) would keep).
  int rows_touching(const std::vector<char>& free) const;

  /// One row per point: sum_i R_i(x_k) u_i = target[k]. The kind's weight is spread over its rows:
  /// each gets weight / x.size(). OpenMP-parallel; rows keep the order of the points.
  void add_value_rows(const std::vector<Vec3>& x, const std::vector<double>& target, double weight);
  /// One row per point: sum_i (direction[k] . grad R_i(y_k)) u_i = target[k], weight / y.size() each.
  void add_gradient_rows(const std::vector<Vec3>& y, const std::vector<Vec3>& direction,
                         const std::vector<double>& target, double weight);
  /// The same rows, with grad R_i at the points that are sites (sites[k] >= 0) taken from `cache`
  /// (filled where missing): the same numbers as computed afresh. The cache must be of this basis.
  void add_gradient_rows(const std::vector<Vec3>& y, const std::vector<Vec3>& direction,
                         const std::vector<double>& target, double weight, const std::vector<int>& sites,
                         GradientCache& cache);

  /// The unknowns (control points touched by a row), the rows renumbered, and the Tikhonov rows
  /// (one per unknown) with total weight `smoothness_weight` (spread over them; 0: none).
  /// With `free` (one flag per control point of the basis), only flagged control points are unknowns:
  /// the others are held (their update is zero), their entries leave the rows, and rows left with no
  /// entry are dropped (a held row is a constant of the objective); each kind's weight is spread over
  /// the rows kept of it. Value rows must have been added before gradient rows
  /// (LeastSquaresSystem::value_rows counts the first rows).
  /// AlgorithmError if no row was added, or none is left.
  LeastSquaresSystem finish(double smoothness_weight, const std::vector<char>* free = nullptr);

 private:
  enum class Kind { value, gradient };
  void add_rows(Kind kind, const std::vector<Vec3>& x, const std::vector<Vec3>* direction,
                const std::vector<double>& target, double weight, const std::vector<int>* sites = nullptr,
                const GradientCache* cache = nullptr);
  void hold_fixed_columns(const std::vector<char>& free);

  const TSplineBasis& basis_;
  std::vector<int> row_begin_{0};
  std::vector<int> column_;  // global control indices until finish()
  std::vector<double> value_, rhs_, weight_;
  int value_rows_ = 0, gradient_rows_ = 0;
};

}  // namespace dtsl
