// The rational cubic T-spline f(x) = sum_i c_i B_i(x) / sum_i B_i(x) (docs/design.md §1; paper §2.1: "the
// T-spline function is piecewise rational ... C2 in the absence of multiple knots"): a basis shared by
// pointer plus one coefficient per control point. This is the level set the evolution moves and the
// polygonizers, foot-point projection and curvature checks read.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "algorithms/tspline/tspline_basis.hpp"
#include "framework/core/implicit.hpp"

namespace dtsl {

class TSpline final : public ImplicitFunction {
 public:
  /// AlgorithmError unless there is one finite coefficient per control point.
  TSpline(std::shared_ptr<const TSplineBasis> basis, std::vector<double> coefficients);

  /// f(x), grad f, Hessian (quotient rule); x outside the domain is clamped onto it. Thread-safe.
  double evaluate(const Vec3& x, Vec3* gradient = nullptr, Mat3* hessian = nullptr) const override {
    return basis_->evaluate(coefficients_.data(), x, gradient, hessian);
  }
  BoundingBox domain() const override { return basis_->domain(); }
  /// True in the leaves whose support coefficients are all positive (convex hull property of the
  /// rational basis): there f > 0 (TSplineBasis::positive_leaves).
  std::function<bool(const Vec3&)> positive_certificate() const override;

  const TSplineBasis& basis() const { return *basis_; }
  const std::shared_ptr<const TSplineBasis>& shared_basis() const { return basis_; }
  const Octree& tmesh() const { return basis_->octree(); }

  /// c_i; the evolution updates them in place (c <- c + dt c'), the size is fixed.
  const std::vector<double>& coefficients() const { return coefficients_; }
  std::vector<double>& coefficients() { return coefficients_; }

 private:
  std::shared_ptr<const TSplineBasis> basis_;
  std::vector<double> coefficients_;
};

/// Quasi-interpolation (docs/design.md §1, initial level set): c_i = g(Greville point of B_i). Exact for
/// linear g on the uniform grid away from the domain boundary; O(h^2) for smooth g.
std::vector<double> quasi_interpolate(const TSplineBasis& basis, const std::function<double(const Vec3&)>& g);

/// Convenience: the T-spline quasi-interpolating g on `basis`.
TSpline quasi_interpolant(std::shared_ptr<const TSplineBasis> basis, const std::function<double(const Vec3&)>& g);

}  // namespace dtsl
