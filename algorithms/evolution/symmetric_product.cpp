#include "algorithms/evolution/symmetric_product.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace dtsl {

SymmetricProduct::SymmetricProduct(const Eigen::SparseMatrix<double>& lower) : lower_(lower) {
  if (lower.rows() != lower.cols() || !lower.isCompressed())
    throw std::invalid_argument("SymmetricProduct: the lower triangle must be square and compressed");
  const int n = static_cast<int>(lower.cols());
  const int* outer = lower.outerIndexPtr();
  const int* row = lower.innerIndexPtr();
  const std::int64_t nonzeros = outer[n];
  int column = 0;
  for (int c = 0; c < kProductChunks; ++c) {
    Chunk chunk;
    chunk.first_column = column;
    const std::int64_t target = nonzeros * (c + 1) / kProductChunks;
    while (column < n && (c + 1 == kProductChunks || outer[column + 1] <= target)) ++column;
    chunk.end_column = column;
    // Every column writes its own row (its sum by symmetry), and each entry its row.
    if (chunk.end_column > chunk.first_column) chunk.last_row = chunk.end_column - 1;
    for (int j = chunk.first_column; j < chunk.end_column; ++j)
      for (int k = outer[j]; k < outer[j + 1]; ++k) {
        if (row[k] < j)
          throw std::invalid_argument("SymmetricProduct: entry (" + std::to_string(row[k]) + ", " +
                                      std::to_string(j) + ") lies above the diagonal");
        chunk.last_row = std::max(chunk.last_row, row[k]);
      }
    chunks_.push_back(chunk);
  }
  partial_.resize(chunks_.size());
  for (std::size_t c = 0; c < chunks_.size(); ++c)
    if (chunks_[c].last_row >= chunks_[c].first_column)
      partial_[c].resize(chunks_[c].last_row - chunks_[c].first_column + 1);
}

void SymmetricProduct::apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const int n = size();
  if (x.size() != n)
    throw std::invalid_argument("SymmetricProduct: x has " + std::to_string(x.size()) + " entries, the matrix " +
                                std::to_string(n) + " columns");
  const int* outer = lower_.outerIndexPtr();
  const int* row = lower_.innerIndexPtr();
  const double* value = lower_.valuePtr();
  const int chunks = static_cast<int>(chunks_.size());
  y.resize(n);
  // One parallel region per product (CG takes thousands): the chunks, then, after the loop's barrier,
  // their sums.
#pragma omp parallel
  {
#pragma omp for schedule(static, 1)
    for (int c = 0; c < chunks; ++c) {
      const Chunk& chunk = chunks_[c];
      if (chunk.last_row < chunk.first_column) continue;
      double* out = partial_[c].data() - chunk.first_column;  // out[i] for rows i in [first_column, last_row]
      partial_[c].setZero();
      for (int j = chunk.first_column; j < chunk.end_column; ++j) {
        const double xj = x[j];
        double column_sum = 0.0;  // sum_i a_ij x_i: row j's entries right of the diagonal, by symmetry
        for (int k = outer[j]; k < outer[j + 1]; ++k) {
          const int i = row[k];
          if (i == j) {
            column_sum += value[k] * xj;
          } else {
            out[i] += value[k] * xj;
            column_sum += value[k] * x[i];
          }
        }
        out[j] += column_sum;
      }
    }
#pragma omp for schedule(static)
    for (int i = 0; i < n; ++i) {
      double sum = 0.0;
      for (int c = 0; c < chunks; ++c) {
        const Chunk& chunk = chunks_[c];
        if (i >= chunk.first_column && i <= chunk.last_row) sum += partial_[c][i - chunk.first_column];
      }
      y[i] = sum;
    }
  }
}

}  // namespace dtsl
