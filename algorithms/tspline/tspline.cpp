#include "algorithms/tspline/tspline.hpp"

#include <cmath>

#include "framework/core/error.hpp"

namespace dtsl {

std::function<bool(const Vec3&)> TSpline::positive_certificate() const {
  auto positive = std::make_shared<const std::vector<char>>(basis_->positive_leaves(coefficients_.data()));
  return [basis = basis_, positive](const Vec3& x) {
    if (!x.allFinite()) return false;
    return (*positive)[std::size_t(basis->leaf_of(x))] != 0;
  };
}

TSpline::TSpline(std::shared_ptr<const TSplineBasis> basis, std::vector<double> coefficients)
    : basis_(std::move(basis)), coefficients_(std::move(coefficients)) {
  if (!basis_) throw AlgorithmError("T-spline: no basis");
  if (int(coefficients_.size()) != basis_->size())
    throw AlgorithmError("T-spline: " + std::to_string(coefficients_.size()) + " coefficients for " +
                         std::to_string(basis_->size()) + " control points");
  for (std::size_t i = 0; i < coefficients_.size(); ++i)
    if (!std::isfinite(coefficients_[i]))
      throw AlgorithmError("T-spline: coefficient " + std::to_string(i) + " is NaN or infinite");
}

std::vector<double> quasi_interpolate(const TSplineBasis& basis, const std::function<double(const Vec3&)>& g) {
  std::vector<double> c(basis.size());
  for (int i = 0; i < basis.size(); ++i) c[i] = g(basis.greville(i));
  return c;
}

TSpline quasi_interpolant(std::shared_ptr<const TSplineBasis> basis, const std::function<double(const Vec3&)>& g) {
  std::vector<double> c = quasi_interpolate(*basis, g);
  return TSpline(std::move(basis), std::move(c));
}

}  // namespace dtsl
