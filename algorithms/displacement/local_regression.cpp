#include "algorithms/displacement/local_regression.hpp"

#include <Eigen/Dense>

namespace dtsl {

namespace {

// The normal matrix M = sum_k w_k x_k x_k^T of the fit with P parameters (3: linear, 6: quadratic) in
// fixed-size matrices (no allocation per vertex), decomposed; false when the samples cannot support it.
template <int P>
struct Fit {
  using Vector = Eigen::Matrix<double, P, 1>;
  using Matrix = Eigen::Matrix<double, P, P>;
  const std::vector<Vec3>& positions;
  Vec3 v, t1, t2;
  double scale;
  Eigen::SelfAdjointEigenSolver<Matrix> eig;

  Vector design(int k) const {
    const Vec3 d = positions[k] - v;
    const double u = d.dot(t1) / scale, w = d.dot(t2) / scale;
    Vector x;
    if constexpr (P == 3) x << 1.0, u, w;
    else x << 1.0, u, w, u * u, u * w, w * w;
    return x;
  }
  bool decompose(const std::vector<std::pair<int, double>>& taps) {
    if (static_cast<int>(taps.size()) < 2 * P) return false;
    Matrix M = Matrix::Zero();
    for (const auto& [k, w] : taps) {
      const Vector x = design(k);
      M.noalias() += w * x * x.transpose();
    }
    eig.compute(M);
    if (eig.info() != Eigen::Success) return false;
    const double lo = eig.eigenvalues()(0), hi = eig.eigenvalues()(P - 1);
    return lo > 1e-8 * hi;
  }
  Vector solve(const Vector& b) const {
    return eig.eigenvectors() * ((eig.eigenvectors().transpose() * b).array() / eig.eigenvalues().array()).matrix();
  }
};

template <int P>
bool fit(std::vector<std::pair<int, double>>& taps, const std::vector<Vec3>& positions, const Vec3& v,
         const Vec3& t1, const Vec3& t2, double scale) {
  Fit<P> fit{positions, v, t1, t2, scale, {}};
  if (!fit.decompose(taps)) return false;
  // e_1^T M^-1 = the first row of M^-1 = V diag(1/lambda) V^T e_1, from the decomposition at hand.
  const typename Fit<P>::Vector row = fit.solve(Fit<P>::Vector::Unit(0));
  for (auto& tap : taps) tap.second *= row.dot(fit.design(tap.first));
  return true;
}

template <int P>
double misfit(const std::vector<std::pair<int, double>>& taps, const std::vector<Vec3>& positions,
              const std::vector<double>& values, const Vec3& v, const Vec3& t1, const Vec3& t2, double scale) {
  Fit<P> fit{positions, v, t1, t2, scale, {}};
  if (!fit.decompose(taps)) return -1.0;
  typename Fit<P>::Vector b = Fit<P>::Vector::Zero();
  double wsum = 0.0;
  for (const auto& [k, w] : taps) b.noalias() += w * values[k] * fit.design(k), wsum += w;
  const typename Fit<P>::Vector c = fit.solve(b);
  // The residuals summed explicitly: sum w y^2 - b^T c would cancel to ~1e-8 on exact data.
  double r2 = 0.0;
  for (const auto& [k, w] : taps) {
    const double r = values[k] - c.dot(fit.design(k));
    r2 += w * r * r;
  }
  return std::sqrt(r2 / wsum);
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

double local_regression_misfit(const std::vector<std::pair<int, double>>& taps, const std::vector<Vec3>& positions,
                               const std::vector<double>& values, const Vec3& v, const Vec3& n, double scale,
                               int degree) {
  const Vec3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
  if (degree == 2) return misfit<6>(taps, positions, values, v, t1, t2, scale);
  if (degree == 1) return misfit<3>(taps, positions, values, v, t1, t2, scale);
  double wsum = 0.0, mean = 0.0, m2 = 0.0;
  for (const auto& [k, w] : taps) wsum += w, mean += w * values[k];
  if (!(wsum > 0)) return -1.0;
  mean /= wsum;
  for (const auto& [k, w] : taps) m2 += w * (values[k] - mean) * (values[k] - mean);
  return std::sqrt(m2 / wsum);
}

}  // namespace dtsl
