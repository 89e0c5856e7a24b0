#include "algorithms/displacement/local_regression.hpp"

#include <Eigen/Dense>

namespace dtsl {

namespace {

// The fit with P parameters (3: linear, 6: quadratic) in fixed-size matrices (no allocation per vertex);
// false when the samples cannot support it.
template <int P>
bool fit(std::vector<std::pair<int, double>>& taps, const std::vector<Vec3>& positions, const Vec3& v,
         const Vec3& t1, const Vec3& t2, double scale) {
  using Vector = Eigen::Matrix<double, P, 1>;
  using Matrix = Eigen::Matrix<double, P, P>;
  if (static_cast<int>(taps.size()) < 2 * P) return false;
  const auto design = [&](int k) {
    const Vec3 d = positions[k] - v;
    const double u = d.dot(t1) / scale, w = d.dot(t2) / scale;
    Vector x;
    if constexpr (P == 3) x << 1.0, u, w;
    else x << 1.0, u, w, u * u, u * w, w * w;
    return x;
  };
  Matrix M = Matrix::Zero();
  for (const auto& [k, w] : taps) {
    const Vector x = design(k);
    M.noalias() += w * x * x.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Matrix> eig(M);
  if (eig.info() != Eigen::Success) return false;
  const double lo = eig.eigenvalues()(0), hi = eig.eigenvalues()(P - 1);
  if (!(lo > 1e-8 * hi)) return false;
  // e_1^T M^-1 = the first row of M^-1 = V diag(1/lambda) V^T e_1, from the decomposition at hand.
  const Vector row =
      eig.eigenvectors() * (eig.eigenvectors().row(0).transpose().array() / eig.eigenvalues().array()).matrix();
  for (auto& tap : taps) tap.second *= row.dot(design(tap.first));
  return true;
}

}  // namespace

int local_regression_weights(std::vector<std::pair<int, double>>& taps, const std::vector<Vec3>& positions,
                             const Vec3& v, const Vec3& n, double scale, int degree) {
  const Vec3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
  if (degree >= 2 && fit<6>(taps, positions, v, t1, t2, scale)) return 2;
  if (degree >= 1 && fit<3>(taps, positions, v, t1, t2, scale)) return 1;
  double sum = 0.0;
  for (const auto& tap : taps) sum += tap.second;
  if (sum > 0)
    for (auto& tap : taps) tap.second /= sum;
  return 0;
}

}  // namespace dtsl
