// The base of the tests' analytic implicit functions: a subclass gives f and its exact gradient
// (eval); the Hessian is the symmetrised central difference of that gradient, and the domain a cube.
#pragma once

#include "framework/core/implicit.hpp"

namespace dtsl::test {

class CentralDifferenceImplicit : public ImplicitFunction {
 public:
  explicit CentralDifferenceImplicit(double half_width = 1.5) {
    box_.extend(Vec3::Constant(-half_width));
    box_.extend(Vec3::Constant(half_width));
  }
  double evaluate(const Vec3& x, Vec3* gradient = nullptr, Mat3* hessian = nullptr) const override {
    Vec3 g;
    const double v = eval(x, g);
    if (gradient) *gradient = g;
    if (hessian) {
      const double h = 1e-5;
      for (int a = 0; a < 3; ++a) {
        Vec3 gp, gm;
        eval(x + h * Vec3::Unit(a), gp);
        eval(x - h * Vec3::Unit(a), gm);
        hessian->col(a) = (gp - gm) / (2 * h);
      }
      *hessian = 0.5 * (*hessian + hessian->transpose()).eval();
    }
    return v;
  }
  BoundingBox domain() const override { return box_; }

 protected:
  /// f(x), and its exact gradient in g.
  virtual double eval(const Vec3& x, Vec3& g) const = 0;

 private:
  BoundingBox box_;
};

}  // namespace dtsl::test
