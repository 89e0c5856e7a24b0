// The product y = N x with a symmetric sparse matrix stored as its lower triangle (the normal equations
// of normal_equations.hpp), for the conjugate gradients of `eigen_cg`. Each stored entry a_ij (i > j) is
// read once and used twice (y_i += a_ij x_j, y_j += a_ij x_i): half the memory traffic of a product with
// the whole matrix, which is what bounds CG's iterations (docs/performance.md, "What keeps it fast").
//
// The columns are cut into kProductChunks runs of about equal nonzeros, each summed into its own buffer
// in column order, and the buffers added in chunk order: the result is the same for every thread count
// (docs/robustness.md), and the chunks run side by side on up to kProductChunks threads.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace dtsl {

class SymmetricProduct {
 public:
  /// Column runs of the product: fixed, so that the sums do not depend on the thread count.
  static constexpr int kProductChunks = 8;

  /// `lower`: the lower triangle (diagonal included) of a symmetric matrix, column-major and compressed
  /// (as normal_equations leaves it). Kept by reference: it must outlive this object. Throws
  /// std::invalid_argument for a matrix that is not square, not compressed, or has an entry above the
  /// diagonal.
  explicit SymmetricProduct(const Eigen::SparseMatrix<double>& lower);

  int size() const { return static_cast<int>(lower_.rows()); }
  /// y = N x (y resized; y must not be x). Throws std::invalid_argument when x's size is not the
  /// matrix's. Not thread-safe: the chunks' buffers are this object's (one product at a time).
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;

 private:
  struct Chunk {
    int first_column = 0, end_column = 0;  ///< columns [first, end)
    int last_row = -1;                     ///< the largest row its columns write (-1: no columns)
  };
  const Eigen::SparseMatrix<double>& lower_;
  std::vector<Chunk> chunks_;
  mutable std::vector<Eigen::VectorXd> partial_;  ///< per chunk, rows [first_column, last_row]
};

}  // namespace dtsl
