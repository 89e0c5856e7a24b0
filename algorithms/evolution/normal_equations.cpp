#include "algorithms/evolution/normal_equations.hpp"

#include <algorithm>
#include <vector>

namespace dtsl {

NormalEquations normal_equations(const LeastSquaresSystem& s) {
  const int n = s.unknowns, m = s.rows();
  // The transpose of A's pattern: for each unknown, the rows (and entries) that touch it.
  std::vector<int> col_begin(n + 1, 0);
  for (int c : s.column) ++col_begin[c + 1];
  for (int j = 0; j < n; ++j) col_begin[j + 1] += col_begin[j];
  std::vector<int> col_row(s.column.size()), col_entry(s.column.size());
  {
    std::vector<int> fill(col_begin.begin(), col_begin.end() - 1);
    for (int r = 0; r < m; ++r)
      for (int e = s.row_begin[r]; e < s.row_begin[r + 1]; ++e) {
        const int k = fill[s.column[e]]++;
        col_row[k] = r;
        col_entry[k] = e;
      }
  }

  NormalEquations out;
  out.rhs = Eigen::VectorXd::Zero(n);
  std::vector<std::vector<std::pair<int, double>>> columns(n);
#pragma omp parallel
  {
    std::vector<double> accumulator(n, 0.0);
    std::vector<int> marker(n, -1), touched;
#pragma omp for schedule(dynamic, 32)
    for (int j = 0; j < n; ++j) {
      touched.clear();
      double rhs = 0.0;
      for (int k = col_begin[j]; k < col_begin[j + 1]; ++k) {
        const int r = col_row[k];
        const double wa = s.weight[r] * s.value[col_entry[k]];
        rhs += wa * s.rhs[r];
        // Columns ascend within a row: the entries from j's own on are the lower triangle.
        for (int e = col_entry[k]; e < s.row_begin[r + 1]; ++e) {
          const int i = s.column[e];
          if (marker[i] != j) {
            marker[i] = j;
            accumulator[i] = 0.0;
            touched.push_back(i);
          }
          accumulator[i] += wa * s.value[e];
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
