#include "algorithms/displacement/local_regression.hpp"

#include <Eigen/Dense>

namespace dtsl {

int local_regression_weights(std::vector<std::pair<int, double>>& taps, const std::vector<Vec3>& positions,
                             const Vec3& v, const Vec3& n, double scale, int degree) {
  const Vec3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
  for (; degree > 0; --degree) {
    const int p = degree == 1 ? 3 : 6;
    if (static_cast<int>(taps.size()) < 2 * p) continue;
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(p, p);
    Eigen::VectorXd x(p);
    const auto design = [&](int k) {
      const Vec3 d = positions[k] - v;
      const double u = d.dot(t1) / scale, w = d.dot(t2) / scale;
      x(0) = 1.0, x(1) = u, x(2) = w;
      if (p == 6) x(3) = u * u, x(4) = u * w, x(5) = w * w;
    };
    for (const auto& [k, w] : taps) design(k), M.noalias() += w * x * x.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(M);
    if (eig.info() != Eigen::Success) continue;
    const double lo = eig.eigenvalues()(0), hi = eig.eigenvalues()(p - 1);
    if (!(lo > 1e-8 * hi)) continue;
    // e_1^T M^-1 = the first row of M^-1 = V diag(1/lambda) V^T e_1, from the decomposition at hand.
    const Eigen::VectorXd row =
        eig.eigenvectors() * (eig.eigenvectors().row(0).transpose().array() / eig.eigenvalues().array()).matrix();
    for (auto& tap : taps) design(tap.first), tap.second *= row.dot(x);
    return degree;
  }
  double sum = 0.0;
  for (const auto& tap : taps) sum += tap.second;
  if (sum > 0)
    for (auto& tap : taps) tap.second /= sum;
  return 0;
}

}  // namespace dtsl
