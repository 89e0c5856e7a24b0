#include "algorithms/evolution/level_set_transfer.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <map>
#include <memory>

#include "framework/core/error.hpp"

namespace dtsl {

Transfer transfer_from_string(const std::string& name) {
  if (name == "least_squares") return Transfer::least_squares;
  if (name == "quasi_interpolation") return Transfer::quasi_interpolation;
  throw ConfigError("transfer: must be one of {least_squares, quasi_interpolation}, got '" + name + "'");
}

const char* to_string(Transfer t) { return t == Transfer::least_squares ? "least_squares" : "quasi_interpolation"; }

Balance balance_of(const Octree& tree) {
  if (is_balanced(tree, Balance::vertex)) return Balance::vertex;
  if (is_balanced(tree, Balance::edge)) return Balance::edge;
  return Balance::face;
}

namespace {

/// The least-squares correction of the changed coefficients: minimise sum_y (f_new(y) - f_old(y))^2
/// over samples y of every leaf where a changed function is active (2^3 sub-cell centres per leaf;
/// each function's support covers several leaves, so each is fitted to dozens of samples), with the
/// unchanged coefficients fixed, so f stays exactly as it was where only they are active.
void fit_changed(const TSpline& old, TSpline& f, const std::vector<char>& changed) {
  const TSplineBasis& basis = f.basis();
  const Octree& tree = basis.octree();
  std::vector<int> unknown(basis.size(), -1);
  int unknowns = 0;
  for (int i = 0; i < basis.size(); ++i)
    if (changed[i]) unknown[i] = unknowns++;
  if (unknowns == 0) return;
  constexpr int kSub = 2;
  struct LeafRows {
    std::vector<Eigen::Triplet<double>> entries;  // row within the leaf, unknown, R_i(y)
    std::vector<double> residual;                 // f_old(y) - f_new(y)
  };
  const int leaves = tree.leaf_count();
  std::vector<LeafRows> rows(leaves);
#pragma omp parallel
  {
    ActiveBasis active;
#pragma omp for schedule(dynamic, 16)
    for (int l = 0; l < leaves; ++l) {
      bool touched = false;
      for (int i : basis.support(l)) touched = touched || changed[i];
      if (!touched) continue;
      const BoundingBox box = tree.leaf_box(l);
      const double h = tree.leaf_side(l) / kSub;
      LeafRows& out = rows[l];
      for (int k = 0; k < kSub * kSub * kSub; ++k) {
        const Vec3 y = box.min + h * Vec3(k % kSub + 0.5, (k / kSub) % kSub + 0.5, k / (kSub * kSub) + 0.5);
        basis.active(y, active);
        const int row = int(out.residual.size());
        for (int a = 0; a < active.size(); ++a)
          if (unknown[active.index[a]] >= 0) out.entries.emplace_back(row, unknown[active.index[a]], active.value[a]);
        out.residual.push_back(old.evaluate(y) - f.evaluate(y));
      }
    }
  }
  // Concatenated in leaf order: the same system for every thread count.
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> residual;
  for (const LeafRows& r : rows) {
    const int offset = int(residual.size());
    for (const auto& t : r.entries) entries.emplace_back(t.row() + offset, t.col(), t.value());
    residual.insert(residual.end(), r.residual.begin(), r.residual.end());
  }
  Eigen::SparseMatrix<double> a(Eigen::Index(residual.size()), unknowns);
  a.setFromTriplets(entries.begin(), entries.end());
  const Eigen::Map<const Eigen::VectorXd> r(residual.data(), Eigen::Index(residual.size()));
  Eigen::SparseMatrix<double> normal = Eigen::SparseMatrix<double>(a.transpose()) * a;
  // A whisper of Tikhonov regularisation keeps the normal equations definite where a changed function
  // meets few samples (on the domain's faces); it moves the fit by far less than the tolerance.
  double largest = 0.0;
  for (int k = 0; k < unknowns; ++k) largest = std::max(largest, normal.coeff(k, k));
  for (int k = 0; k < unknowns; ++k) normal.coeffRef(k, k) += 1e-9 * largest;
  const Eigen::VectorXd rhs = a.transpose() * r;
  // CG lowers the least-squares objective at every iteration, so even a capped solve improves on the
  // quasi-interpolant it starts from (delta = 0).
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
  cg.setTolerance(1e-6);
  cg.setMaxIterations(2000);
  cg.compute(normal);
  const Eigen::VectorXd delta = cg.solve(rhs);
  if (!delta.allFinite()) return;  // keep the quasi-interpolant
  std::vector<double>& c = f.coefficients();
  for (int i = 0; i < basis.size(); ++i)
    if (unknown[i] >= 0) c[i] += delta[unknown[i]];
}

}  // namespace

TSpline transfer_level_set(const TSpline& old, Octree refined, Transfer method) {
  auto basis = std::make_shared<TSplineBasis>(std::move(refined));
  const TSplineBasis& previous = old.basis();
  std::map<Int3, int> old_index;
  for (int i = 0; i < previous.size(); ++i) old_index.emplace(previous.vertex(i), i);
  std::vector<double> c(basis->size());
  std::vector<char> changed(basis->size(), 0);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < basis->size(); ++i) {
    const auto it = old_index.find(basis->vertex(i));
    if (it != old_index.end() && previous.knots(it->second) == basis->knots(i)) {
      c[i] = old.coefficients()[it->second];
    } else {
      c[i] = old.evaluate(basis->greville(i));
      changed[i] = 1;
    }
  }
  TSpline f(std::move(basis), std::move(c));
  if (method == Transfer::least_squares) fit_changed(old, f, changed);
  return f;
}

}  // namespace dtsl
