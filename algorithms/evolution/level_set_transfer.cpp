#include "algorithms/evolution/level_set_transfer.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <algorithm>
#include <map>
#include <memory>
#include <utility>

#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"

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
/// Least-squares CG on the sample matrix itself: A^T A is never formed (it would be several times
/// larger than A on a 20k-point T-mesh).
void fit_changed(const TSpline& old, TSpline& f, const std::vector<char>& changed, TransferReport& report) {
  const TSplineBasis& basis = f.basis();
  const Octree& tree = basis.octree();
  std::vector<int> unknown(basis.size(), -1);
  int unknowns = 0;
  for (int i = 0; i < basis.size(); ++i)
    if (changed[i]) unknown[i] = unknowns++;
  if (unknowns == 0) return;
  constexpr int kSub = 2;
  struct LeafRows {
    std::vector<int> begin;      // row r's entries are [begin[r], begin[r + 1])
    std::vector<int> column;     // unknown
    std::vector<double> value;   // R_i(y)
    std::vector<double> residual;  // f_old(y) - f_new(y)
  };
  const int leaves = tree.leaf_count();
  std::vector<LeafRows> rows(leaves);
#pragma omp parallel
  {
    ActiveBasis active;
    std::vector<std::pair<int, double>> entries;
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
        out.begin.push_back(int(out.column.size()));
        entries.clear();
        for (int a = 0; a < active.size(); ++a)
          if (unknown[active.index[a]] >= 0) entries.emplace_back(unknown[active.index[a]], active.value[a]);
        std::sort(entries.begin(), entries.end());  // the row-major matrix takes ascending columns
        for (const auto& [column, value] : entries) {
          out.column.push_back(column);
          out.value.push_back(value);
        }
        out.residual.push_back(old.evaluate(y) - f.evaluate(y));
      }
    }
  }
  // Joined in leaf order (the same system for every thread count), each leaf's rows freed as they go.
  std::size_t samples = 0, entries = 0;
  for (const LeafRows& r : rows) {
    samples += r.residual.size();
    entries += r.column.size();
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> a(static_cast<Eigen::Index>(samples), unknowns);
  a.reserve(Eigen::Index(entries));
  Eigen::VectorXd residual(static_cast<Eigen::Index>(samples));
  Eigen::Index row = 0;
  for (LeafRows& r : rows) {
    for (std::size_t k = 0; k < r.residual.size(); ++k, ++row) {
      a.startVec(row);
      const int end = k + 1 < r.begin.size() ? r.begin[k + 1] : int(r.column.size());
      for (int e = r.begin[k]; e < end; ++e) a.insertBack(row, r.column[e]) = r.value[e];
      residual[row] = r.residual[k];
    }
    r = LeafRows();
  }
  a.finalize();
  // CG on the normal equations lowers the least-squares objective at every iteration, so even a
  // capped solve improves on the quasi-interpolant it starts from (delta = 0).
  Eigen::LeastSquaresConjugateGradient<Eigen::SparseMatrix<double, Eigen::RowMajor>> cg;
  cg.setTolerance(1e-6);
  cg.setMaxIterations(2000);
  cg.compute(a);
  const Eigen::VectorXd delta = cg.solve(residual);
  report.samples = int(samples);
  report.iterations = int(cg.iterations());
  report.cg_error = cg.error();
  report.converged = cg.info() == Eigen::Success;
  if (!delta.allFinite()) {  // keep the quasi-interpolant, and say so
    report.converged = false;
    return;
  }
  std::vector<double>& c = f.coefficients();
  for (int i = 0; i < basis.size(); ++i)
    if (unknown[i] >= 0) c[i] += delta[unknown[i]];
}

}  // namespace

nlohmann::json to_json(const TransferReport& r) {
  nlohmann::json j = {{"method", r.method}, {"changed", r.changed}, {"seconds", r.seconds}};
  if (r.method == "least_squares") {
    j["samples"] = r.samples;
    j["cg_iterations"] = r.iterations;
    j["cg_error"] = r.cg_error;
    j["converged"] = r.converged;
  }
  return j;
}

TSpline transfer_level_set(const TSpline& old, Octree refined, Transfer method, TransferReport* report) {
  Stopwatch clock;
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
  TransferReport record;
  record.method = to_string(method);
  for (char k : changed) record.changed += k;
  if (method == Transfer::least_squares) fit_changed(old, f, changed, record);
  record.seconds = clock.seconds();
  if (report) *report = record;
  return f;
}

}  // namespace dtsl
