// An implicit function f: R^3 -> R with value, gradient and Hessian: what the polygonizers, the Newton
// projection and the curvature checks need of a level set (paper §2.2: "f(x) and grad f(x) are
// available for any point x"). Negative inside, positive outside; grad f / |grad f| is the outward normal.
#pragma once

#include <functional>

#include <Eigen/Core>

#include "framework/core/types.hpp"

namespace dtsl {

using Mat3 = Eigen::Matrix3d;

class ImplicitFunction {
 public:
  virtual ~ImplicitFunction() = default;

  /// f(x); and, where the pointers are non-null, grad f(x) and the Hessian of f at x.
  virtual double evaluate(const Vec3& x, Vec3* gradient = nullptr, Mat3* hessian = nullptr) const = 0;

  /// The box outside which f is not defined (queries there are clamped or extrapolated).
  virtual BoundingBox domain() const = 0;

  /// A cheap test that is true only where f(x) > 0 for certain (false: not known), for samplers that
  /// need f's sign far from the zero set but its value only near it (marching_cubes). Empty (the
  /// default): no such test, every sample is evaluated. Thread-safe to call; valid while f lives
  /// unchanged.
  virtual std::function<bool(const Vec3&)> positive_certificate() const { return {}; }

  double value(const Vec3& x) const { return evaluate(x); }
  Vec3 gradient(const Vec3& x) const {
    Vec3 g;
    evaluate(x, &g);
    return g;
  }
};

}  // namespace dtsl
