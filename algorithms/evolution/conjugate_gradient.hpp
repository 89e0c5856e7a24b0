// Conjugate gradients with the Jacobi preconditioner (Hestenes & Stiefel 1952; Saad, "Iterative methods
// for sparse linear systems", Alg. 9.1) on a symmetric positive definite matrix given by its lower
// triangle, the normal equations of the level-set stage (`eigen_cg`). The products go through
// SymmetricProduct (half the memory traffic of a product with the whole matrix); every other operation is
// serial, so the iterates are the same for every thread count.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace dtsl {

struct ConjugateGradientResult {
  int iterations = 0;
  /// |r| / |g| with r the recurrence's residual (N x - g in exact arithmetic, as Eigen's CG reports it;
  /// 0 for g = 0)
  double relative_residual = 0.0;
  bool converged = false;          ///< relative_residual <= tolerance
};

/// Solves N x = g from the guess in `x` (resized to zero when its size is wrong), stopping when
/// |N x - g| < tolerance |g| or after max_iterations, or where N is not positive definite along a search
/// direction (not converged). `lower`: N's lower triangle, compressed, column-major.
ConjugateGradientResult jacobi_conjugate_gradient(const Eigen::SparseMatrix<double>& lower, const Eigen::VectorXd& g,
                                                  double tolerance, int max_iterations, Eigen::VectorXd& x);

}  // namespace dtsl
