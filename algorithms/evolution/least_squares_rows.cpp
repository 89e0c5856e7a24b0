#include "algorithms/evolution/least_squares_rows.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "framework/core/error.hpp"

namespace dtsl {

// ---------------------------------------------------------------------------------------------------

double LeastSquaresSystem::objective(const Eigen::VectorXd& u) const {
  double sum = 0.0;
  for (int r = 0; r < rows(); ++r) {
    double a = -rhs[r];
    for (int e = row_begin[r]; e < row_begin[r + 1]; ++e) a += value[e] * u[column[e]];
    sum += weight[r] * a * a;
  }
  return sum;
}

Eigen::VectorXd LeastSquaresSystem::normal_residual(const Eigen::VectorXd& u) const {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(unknowns);
  for (int r = 0; r < rows(); ++r) {
    double a = -rhs[r];
    for (int e = row_begin[r]; e < row_begin[r + 1]; ++e) a += value[e] * u[column[e]];
    a *= weight[r];
    for (int e = row_begin[r]; e < row_begin[r + 1]; ++e) g[column[e]] += value[e] * a;
  }
  return g;
}

double LeastSquaresSystem::relative_residual(const Eigen::VectorXd& u) const {
  const double residual = normal_residual(u).norm();
  const double scale = normal_residual(Eigen::VectorXd::Zero(unknowns)).norm();  // |A^T W b|
  if (scale == 0.0) return residual == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
  return residual / scale;
}

std::vector<double> LeastSquaresSystem::expand(const Eigen::VectorXd& u, int controls) const {
  std::vector<double> full(controls, 0.0);
  for (int k = 0; k < unknowns; ++k) full[control[k]] = u[k];
  return full;
}

Eigen::VectorXd LeastSquaresSystem::restrict(const std::vector<double>& full) const {
  Eigen::VectorXd u(unknowns);
  for (int k = 0; k < unknowns; ++k) u[k] = control[k] < int(full.size()) ? full[control[k]] : 0.0;
  return u;
}

// ---------------------------------------------------------------------------------------------------

void LeastSquaresBuilder::add_value_rows(const std::vector<Vec3>& x, const std::vector<double>& target,
                                         double weight) {
  add_rows(Kind::value, x, nullptr, target, weight);
}

void LeastSquaresBuilder::add_gradient_rows(const std::vector<Vec3>& y, const std::vector<Vec3>& direction,
                                            const std::vector<double>& target, double weight) {
  if (direction.size() != y.size()) throw AlgorithmError("least squares: one direction per gradient row needed");
  add_rows(Kind::gradient, y, &direction, target, weight);
}

void GradientCache::fill(const std::vector<Vec3>& x, const std::vector<int>& sites) {
  if (sites.size() != x.size()) throw AlgorithmError("gradient cache: one site number per point needed");
  for (int s : sites)
    if (s >= 0 && std::size_t(s) >= slot_.size())
      throw AlgorithmError("gradient cache: site " + std::to_string(s) + " out of range [0, " +
                           std::to_string(slot_.size()) + ")");
  if (full_) return;  // the rows compute the rest afresh, once
  std::vector<std::size_t> missing;
  for (std::size_t k = 0; k < sites.size(); ++k) {
    const int s = sites[k];
    if (s < 0) continue;
    if (slot_[std::size_t(s)] == -1) {
      slot_[std::size_t(s)] = -2;  // listed once even if repeated
      missing.push_back(k);
    }
  }
  const long n = long(missing.size());
  std::vector<std::vector<int>> index(missing.size());
  std::vector<std::vector<Vec3>> gradient(missing.size());
#pragma omp parallel
  {
    ActiveBasis active;
#pragma omp for schedule(dynamic, 64)
    for (long m = 0; m < n; ++m) {
      basis_.active(x[missing[std::size_t(m)]], active, false);
      index[std::size_t(m)] = active.index;
      gradient[std::size_t(m)] = active.gradient;
    }
  }
  for (std::size_t m = 0; m < missing.size(); ++m) {
    if (bytes() + index[m].size() * (sizeof(int) + sizeof(Vec3)) > max_bytes_) {
      slot_[std::size_t(sites[missing[m]])] = -1;  // over budget: computed afresh when asked
      full_ = true;
      continue;
    }
    slot_[std::size_t(sites[missing[m]])] = int(begin_.size()) - 1;
    index_.insert(index_.end(), index[m].begin(), index[m].end());
    gradient_.insert(gradient_.end(), gradient[m].begin(), gradient[m].end());
    begin_.push_back(int(index_.size()));
  }
}

void LeastSquaresBuilder::add_gradient_rows(const std::vector<Vec3>& y, const std::vector<Vec3>& direction,
                                            const std::vector<double>& target, double weight,
                                            const std::vector<int>& sites, GradientCache& cache) {
  if (direction.size() != y.size()) throw AlgorithmError("least squares: one direction per gradient row needed");
  if (&cache.basis() != &basis_) throw AlgorithmError("least squares: the gradient cache is of another basis");
  cache.fill(y, sites);
  add_rows(Kind::gradient, y, &direction, target, weight, &sites, &cache);
}

void LeastSquaresBuilder::add_rows(Kind kind, const std::vector<Vec3>& x, const std::vector<Vec3>* direction,
                                   const std::vector<double>& target, double weight, const std::vector<int>* sites,
                                   const GradientCache* cache) {
  if (target.size() != x.size()) throw AlgorithmError("least squares: one target per row needed");
  if (x.empty()) return;
  // Each thread fills its own block of consecutive points; blocks are appended in order, so the rows
  // come out in point order whatever the thread count.
  int threads = 1;
#ifdef _OPENMP
  threads = std::max(1, std::min(omp_get_max_threads(), int(x.size() / 64) + 1));
#endif
  struct Block {
    std::vector<int> count, column;  // entries of each row (one row per point), their control indices
    std::vector<double> value;
  };
  std::vector<Block> blocks(threads);
  const long n = long(x.size());
#pragma omp parallel num_threads(threads)
  {
    int t = 0;
#ifdef _OPENMP
    t = omp_get_thread_num();
#endif
    const long begin = n * t / threads, end = n * (t + 1) / threads;
    Block& b = blocks[t];
    ActiveBasis active;
    // Reserved up front: growing these by doubling is ~8 % memmove in a single-threaded reconstruction's
    // profile (1 % reserved, with the allocator's top pad). A cubic
    // T-spline has 64 active functions at a generic point, more near T-junctions (53-70 per row, mean,
    // in fandisk's evolution steps).
    b.count.reserve(end - begin);
    b.column.reserve(std::size_t(end - begin) * 80);
    b.value.reserve(std::size_t(end - begin) * 80);
    const auto entry = [&](int column, double value) {
      b.column.push_back(column);
      b.value.push_back(value);
    };
    for (long k = begin; k < end; ++k) {
      const std::size_t first = b.column.size();
      if (cache && (*sites)[std::size_t(k)] >= 0 && cache->has((*sites)[std::size_t(k)])) {  // a cached site
        const int site = (*sites)[std::size_t(k)], size = cache->size(site);
        const int* index = cache->index(site);
        const Vec3* gradient = cache->gradient(site);
        for (int e = 0; e < size; ++e) entry(index[e], (*direction)[k].dot(gradient[e]));
      } else {
        basis_.active(x[k], active, false);
        for (int e = 0; e < active.size(); ++e)
          entry(active.index[e], kind == Kind::value ? active.value[e] : (*direction)[k].dot(active.gradient[e]));
      }
      b.count.push_back(int(b.column.size() - first));
    }
  }
  const int rows = int(n);
  const double row_weight = weight / double(rows);
  std::size_t entries = 0;
  for (const Block& b : blocks) entries += b.column.size();
  row_begin_.reserve(row_begin_.size() + std::size_t(rows));
  column_.reserve(column_.size() + entries);
  value_.reserve(value_.size() + entries);
  rhs_.reserve(rhs_.size() + std::size_t(rows));
  weight_.reserve(weight_.size() + std::size_t(rows));
  for (const Block& b : blocks) {
    for (int c : b.count) row_begin_.push_back(row_begin_.back() + c);
    column_.insert(column_.end(), b.column.begin(), b.column.end());
    value_.insert(value_.end(), b.value.begin(), b.value.end());
  }
  rhs_.insert(rhs_.end(), target.begin(), target.end());
  weight_.insert(weight_.end(), std::size_t(rows), row_weight);
  (kind == Kind::value ? value_rows_ : gradient_rows_) += rows;
}

int LeastSquaresBuilder::rows_touching(const std::vector<char>& free) const {
  int touching = 0;
  for (std::size_t r = 0; r + 1 < row_begin_.size(); ++r)
    for (int e = row_begin_[r]; e < row_begin_[r + 1]; ++e)
      if (free[std::size_t(column_[std::size_t(e)])]) {
        ++touching;
        break;
      }
  return touching;
}

void LeastSquaresBuilder::hold_fixed_columns(const std::vector<char>& free) {
  if (free.size() != std::size_t(basis_.size()))
    throw AlgorithmError("least squares: " + std::to_string(free.size()) + " free flags for " +
                         std::to_string(basis_.size()) + " control points");
  // Compacted in place, row by row in order: the kept entries of a row keep their order.
  std::size_t entries = 0, rows = 0;
  int value_rows = 0, gradient_rows = 0;
  const std::size_t count = rhs_.size();
  int begin = row_begin_[0];  // row r's original start (row_begin_ is overwritten behind the reading)
  for (std::size_t r = 0; r < count; ++r) {
    const std::size_t first = entries;
    const int end = row_begin_[r + 1];
    for (int e = begin; e < end; ++e)
      if (free[std::size_t(column_[std::size_t(e)])]) {
        column_[entries] = column_[std::size_t(e)];
        value_[entries] = value_[std::size_t(e)];
        ++entries;
      }
    begin = end;
    if (entries == first) continue;  // no free column: a constant, dropped
    rhs_[rows] = rhs_[r];
    weight_[rows] = weight_[r];
    row_begin_[rows + 1] = int(entries);
    ++rows;
    (int(r) < value_rows_ ? value_rows : gradient_rows) += 1;
  }
  column_.resize(entries);
  value_.resize(entries);
  rhs_.resize(rows);
  weight_.resize(rows);
  row_begin_.resize(rows + 1);
  if (rhs_.empty()) throw AlgorithmError("least squares: no row touches a free control point");
  // Each kind's weight spread over the rows kept, as if only they had been added: the balance of the
  // terms against the smoothness rows (spread over the free unknowns) is that of a fit of the free part
  // alone.
  const double value_scale = value_rows > 0 ? double(value_rows_) / value_rows : 1.0;
  const double gradient_scale = gradient_rows > 0 ? double(gradient_rows_) / gradient_rows : 1.0;
  for (std::size_t r = 0; r < rows; ++r) weight_[r] *= int(r) < value_rows ? value_scale : gradient_scale;
  value_rows_ = value_rows;
  gradient_rows_ = gradient_rows;
}

LeastSquaresSystem LeastSquaresBuilder::finish(double smoothness_weight, const std::vector<char>* free) {
  if (rhs_.empty()) throw AlgorithmError("least squares: no rows");
  if (free) hold_fixed_columns(*free);
  LeastSquaresSystem s;
  // Unknowns: the control points touched by a row, in control order (deterministic).
  std::vector<int> unknown_of(basis_.size(), -1);
  for (int c : column_) unknown_of[c] = 0;
  for (int i = 0; i < basis_.size(); ++i)
    if (unknown_of[i] == 0) {
      unknown_of[i] = int(s.control.size());
      s.control.push_back(i);
    }
  s.unknowns = int(s.control.size());
  s.row_begin = std::move(row_begin_);
  s.column = std::move(column_);
  for (int& c : s.column) c = unknown_of[c];
  s.value = std::move(value_);
  // Columns ascending within each row (normal_equations() then visits only the lower triangle). The
  // rows of one leaf's samples come one after another with the same columns in the same order (the
  // leaf's active control points): the sorting permutation is computed once per such run.
  {
    const int rows = int(s.row_begin.size()) - 1;
    std::vector<int> run_start;  // rows where the column list differs from the previous row's
    for (int r = 0; r < rows; ++r) {
      const int a = r > 0 ? s.row_begin[r - 1] : 0, b = s.row_begin[r], size = s.row_begin[r + 1] - b;
      if (r == 0 || b - a != size || !std::equal(s.column.begin() + a, s.column.begin() + b, s.column.begin() + b))
        run_start.push_back(r);
    }
    run_start.push_back(rows);
    const int runs = int(run_start.size()) - 1;
#pragma omp parallel
    {
      std::vector<int> order, sorted_column;
      std::vector<double> sorted_value;
#pragma omp for schedule(dynamic, 64)
      for (int q = 0; q < runs; ++q) {
        const int first = s.row_begin[run_start[q]], size = s.row_begin[run_start[q] + 1] - first;
        order.resize(size);
        for (int i = 0; i < size; ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](int x, int y) { return s.column[first + x] < s.column[first + y]; });
        sorted_column.resize(size);
        for (int i = 0; i < size; ++i) sorted_column[i] = s.column[first + order[i]];
        sorted_value.resize(size);
        for (int r = run_start[q]; r < run_start[q + 1]; ++r) {
          const int begin = s.row_begin[r];
          for (int i = 0; i < size; ++i) sorted_value[i] = s.value[begin + order[i]];
          std::copy(sorted_column.begin(), sorted_column.end(), s.column.begin() + begin);
          std::copy(sorted_value.begin(), sorted_value.end(), s.value.begin() + begin);
        }
      }
    }
  }
  s.rhs = std::move(rhs_);
  s.weight = std::move(weight_);
  s.value_rows = value_rows_;
  s.gradient_rows = gradient_rows_;

  if (smoothness_weight > 0.0) {
    // R = I: one row per unknown. Room for exactly these rows: one copy of the entries, not a doubling.
    const std::size_t extra_rows = std::size_t(s.unknowns);
    s.column.reserve(s.column.size() + extra_rows);
    s.value.reserve(s.value.size() + extra_rows);
    s.row_begin.reserve(s.row_begin.size() + extra_rows);
    s.rhs.reserve(s.rhs.size() + extra_rows);
    s.weight.reserve(s.weight.size() + extra_rows);
    const double w = smoothness_weight / s.unknowns;
    for (int k = 0; k < s.unknowns; ++k) {
      s.column.push_back(k);
      s.value.push_back(1.0);
      s.row_begin.push_back(int(s.column.size()));
      s.rhs.push_back(0.0);
      s.weight.push_back(w);
      ++s.smoothness_rows;
    }
  }
  row_begin_ = {0};
  value_rows_ = gradient_rows_ = 0;
  return s;
}

}  // namespace dtsl
