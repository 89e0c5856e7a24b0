#include "algorithms/evolution/conjugate_gradient.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "algorithms/evolution/symmetric_product.hpp"

namespace dtsl {

ConjugateGradientResult jacobi_conjugate_gradient(const Eigen::SparseMatrix<double>& lower, const Eigen::VectorXd& g,
                                                  double tolerance, int max_iterations, Eigen::VectorXd& x) {
  const SymmetricProduct product(lower);
  const int n = product.size();
  ConjugateGradientResult result;
  if (x.size() != n) x = Eigen::VectorXd::Zero(n);
  const double g_norm2 = g.squaredNorm();
  if (g_norm2 == 0.0) {
    x.setZero();
    result.converged = true;
    return result;
  }
  // Jacobi: the inverse diagonal (1 where a diagonal entry is zero, so it cannot divide by zero).
  Eigen::VectorXd inverse_diagonal = Eigen::VectorXd::Ones(n);
  const Eigen::VectorXd diagonal = lower.diagonal();
  for (int i = 0; i < n; ++i)
    if (diagonal[i] != 0.0) inverse_diagonal[i] = 1.0 / diagonal[i];

  const double threshold = std::max(tolerance * tolerance * g_norm2, std::numeric_limits<double>::min());
  Eigen::VectorXd residual, product_p;
  product.apply(x, residual);
  residual = g - residual;
  double residual_norm2 = residual.squaredNorm();
  Eigen::VectorXd p = inverse_diagonal.cwiseProduct(residual), z;
  double rz = residual.dot(p);
  int iteration = 0;
  while (residual_norm2 >= threshold && iteration < max_iterations) {
    product.apply(p, product_p);
    const double curvature = p.dot(product_p);
    if (!(curvature > 0.0)) break;  // N is not positive definite along p (or not finite): no step
    const double alpha = rz / curvature;
    x += alpha * p;
    residual -= alpha * product_p;
    residual_norm2 = residual.squaredNorm();
    ++iteration;
    if (residual_norm2 < threshold) break;
    z = inverse_diagonal.cwiseProduct(residual);
    const double rz_old = rz;
    rz = residual.dot(z);
    p = z + (rz / rz_old) * p;
  }
  result.iterations = iteration;
  result.relative_residual = std::sqrt(residual_norm2 / g_norm2);
  result.converged = result.relative_residual <= tolerance;
  return result;
}

}  // namespace dtsl
