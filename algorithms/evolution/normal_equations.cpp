#include "algorithms/evolution/normal_equations.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

namespace dtsl {

namespace {

/// Maximal runs of consecutive rows with the same columns: an evolution step's zero-set and band
/// samples come leaf by leaf, and the samples of one leaf share its active control points, so their
/// rows form runs; rows in input order (the final refinement's data rows) mostly form runs of one.
/// Run q is rows [begin[q], begin[q + 1]).
std::vector<int> row_runs(const LeastSquaresSystem& s) {
  const int m = s.rows();
  std::vector<int> begin;
  begin.reserve(m / 4 + 2);
  for (int r = 0; r < m; ++r) {
    if (r > 0) {
      const int a = s.row_begin[r - 1], b = s.row_begin[r];
      const int size = b - a;
      if (size == s.row_begin[r + 1] - b && size > 0 &&
          std::memcmp(&s.column[a], &s.column[b], sizeof(int) * std::size_t(size)) == 0)
        continue;
    }
    begin.push_back(r);
  }
  begin.push_back(m);
  return begin;
}

}  // namespace

NormalEquations normal_equations(const LeastSquaresSystem& s) {
  const int n = s.unknowns;
  const std::vector<int> run = row_runs(s);
  const int runs = int(run.size()) - 1;

  // The transpose of the runs' pattern: for each unknown, the runs that touch it and its position
  // among the run's columns.
  std::vector<int> col_begin(n + 1, 0);
  for (int q = 0; q < runs; ++q)
    for (int e = s.row_begin[run[q]]; e < s.row_begin[run[q] + 1]; ++e) ++col_begin[s.column[e] + 1];
  for (int j = 0; j < n; ++j) col_begin[j + 1] += col_begin[j];
  std::vector<int> col_run(col_begin[n]), col_local(col_begin[n]);
  {
    std::vector<int> fill(col_begin.begin(), col_begin.end() - 1);
    for (int q = 0; q < runs; ++q) {
      const int first = s.row_begin[run[q]];
      for (int e = first; e < s.row_begin[run[q] + 1]; ++e) {
        const int k = fill[s.column[e]]++;
        col_run[k] = q;
        col_local[k] = e - first;
      }
    }
  }

  // Column j of the lower triangle: for each run through j, sum over its rows of w a_rj a_r[i >= j],
  // a dense product over the run's contiguous values, then one scatter per run (not per row).
  NormalEquations out;
  out.rhs = Eigen::VectorXd::Zero(n);
  std::vector<std::vector<std::pair<int, double>>> columns(n);
#pragma omp parallel
  {
    std::vector<double> accumulator(n, 0.0), sum;
    std::vector<int> marker(n, -1), touched;
#pragma omp for schedule(dynamic, 32)
    for (int j = 0; j < n; ++j) {
      touched.clear();
      double rhs = 0.0;
      for (int k = col_begin[j]; k < col_begin[j + 1]; ++k) {
        const int q = col_run[k], local = col_local[k];
        const int first_row = run[q], last_row = run[q + 1];
        const int* cols = &s.column[s.row_begin[first_row]];
        const int width = s.row_begin[first_row + 1] - s.row_begin[first_row];
        // Columns ascend within a row: the entries from j's own on are the lower triangle.
        const int tail = width - local;
        sum.assign(std::size_t(tail), 0.0);
        for (int r = first_row; r < last_row; ++r) {
          const double* a = &s.value[s.row_begin[r]];
          const double wa = s.weight[r] * a[local];
          rhs += wa * s.rhs[r];
          for (int i = 0; i < tail; ++i) sum[i] += wa * a[local + i];
        }
        for (int i = 0; i < tail; ++i) {
          const int c = cols[local + i];
          if (marker[c] != j) {
            marker[c] = j;
            accumulator[c] = 0.0;
            touched.push_back(c);
          }
          accumulator[c] += sum[i];
        }
      }
      out.rhs[j] = rhs;
      std::sort(touched.begin(), touched.end());
      auto& column = columns[j];
      column.reserve(touched.size());
      for (int i : touched) column.emplace_back(i, accumulator[i]);
    }
  }

  std::size_t nnz = 0;
  for (const auto& c : columns) nnz += c.size();
  out.lower.resize(n, n);
  out.lower.resizeNonZeros(Eigen::Index(nnz));
  int* outer = out.lower.outerIndexPtr();
  int* inner = out.lower.innerIndexPtr();
  double* values = out.lower.valuePtr();
  std::size_t k = 0;
  for (int j = 0; j < n; ++j) {
    outer[j] = int(k);
    for (const auto& [i, v] : columns[j]) {
      inner[k] = i;
      values[k] = v;
      ++k;
    }
  }
  outer[n] = int(k);
  return out;
}

}  // namespace dtsl
