// The normal equations A^T W A u = A^T W b of a LeastSquaresSystem, for the solvers that factorise or
// iterate on them (`eigen_ldlt`, `eigen_cg`). Sparse and symmetric positive definite (docs/design.md §1)
// as long as every unknown has a smoothness row or enough other rows.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "algorithms/evolution/least_squares_rows.hpp"

namespace dtsl {

struct NormalEquations {
  /// A^T W A, lower triangle (diagonal included) only, column-major with sorted indices.
  Eigen::SparseMatrix<double> lower;
  Eigen::VectorXd rhs;  ///< A^T W b
};

/// Column by column with a dense accumulator (OpenMP-parallel over columns; each entry summed over the
/// rows of a run in order, then run by run in order, so the same for every thread count), no triplet
/// list and no sort of the whole matrix. Runs of consecutive rows with the same columns (an evolution
/// step's zero-set and band samples of one T-mesh leaf) are summed densely and scattered once per run. Relies on the columns ascending within each row (as
/// LeastSquaresBuilder::finish leaves them).
NormalEquations normal_equations(const LeastSquaresSystem& system);

}  // namespace dtsl
