// Analytic base implicits for the displacement tests: sphere (signed distance, exact Hessian),
// ellipsoid (algebraic), rounded box (signed distance) and a dumbbell of revolution with a thin, concave
// neck (the small-radius feature of the curvature check). Hessians not written out are central
// differences of the exact gradient.
#pragma once

#include <cmath>

#include "framework/core/implicit.hpp"
#include "tests/support/analytic_implicit.hpp"

namespace dtsl::test {

using Analytic = CentralDifferenceImplicit;  // cube [-1.5, 1.5]^3

/// |x| - r.
class SphereSdf final : public Analytic {
 public:
  explicit SphereSdf(double r) : r_(r) {}
  double evaluate(const Vec3& x, Vec3* g = nullptr, Mat3* h = nullptr) const override {
    const double n = x.norm();
    if (g) *g = x / n;
    if (h) *h = (Mat3::Identity() - x * x.transpose() / (n * n)) / n;
    return n - r_;
  }

 protected:
  double eval(const Vec3& x, Vec3& g) const override { return evaluate(x, &g); }

 private:
  double r_;
};

/// x^2/a^2 + y^2/b^2 + z^2/c^2 - 1.
class Ellipsoid final : public Analytic {
 public:
  explicit Ellipsoid(const Vec3& axes) : inv2_(axes.cwiseProduct(axes).cwiseInverse()) {}

 protected:
  double eval(const Vec3& x, Vec3& g) const override {
    g = 2.0 * x.cwiseProduct(inv2_);
    return x.cwiseProduct(x).dot(inv2_) - 1.0;
  }

 private:
  Vec3 inv2_;
};

/// Box of half sides b with edges rounded at radius r (signed distance).
class RoundedBox final : public Analytic {
 public:
  RoundedBox(const Vec3& half, double r) : b_(half - Vec3::Constant(r)), r_(r) {}

 protected:
  double eval(const Vec3& x, Vec3& g) const override {
    const Vec3 q = x.cwiseAbs() - b_;
    const Vec3 qp = q.cwiseMax(0.0);
    const double outside = qp.norm();
    const double inside = std::min(q.maxCoeff(), 0.0);
    if (outside > 0) {
      g = qp / outside;
    } else {
      int a;
      q.maxCoeff(&a);
      g = Vec3::Unit(a);
    }
    for (int a = 0; a < 3; ++a)
      if (x[a] < 0) g[a] = -g[a];
    return outside + inside - r_;
  }

 private:
  Vec3 b_;
  double r_;
};

/// y^2 + z^2 - (1 - x^2) (n^2 + k x^2): a closed surface of revolution about x whose radius is n at
/// the neck x = 0 and grows towards two bulbs; the neck is concave along x with a small radius.
class Dumbbell final : public Analytic {
 public:
  Dumbbell(double neck, double k) : n2_(neck * neck), k_(k) {}

 protected:
  double eval(const Vec3& x, Vec3& g) const override {
    const double t = x.x() * x.x();
    const double P = (1 - t) * (n2_ + k_ * t);
    const double dP = 2 * x.x() * (-(n2_ + k_ * t) + (1 - t) * k_);
    g = Vec3(-dP, 2 * x.y(), 2 * x.z());
    return x.y() * x.y() + x.z() * x.z() - P;
  }

 private:
  double n2_, k_;
};

/// |x| - r - a cos(k x) cos(k y) cos(k z): a sphere with bumps of wavelength 2 pi / k (a lumpy base
/// surface, as a coarse level set is).
class BumpySphere final : public Analytic {
 public:
  BumpySphere(double r, double a, double k) : r_(r), a_(a), k_(k) {}

 protected:
  double eval(const Vec3& x, Vec3& g) const override {
    const double cx = std::cos(k_ * x.x()), cy = std::cos(k_ * x.y()), cz = std::cos(k_ * x.z());
    const double sx = std::sin(k_ * x.x()), sy = std::sin(k_ * x.y()), sz = std::sin(k_ * x.z());
    g = x / x.norm() + a_ * k_ * Vec3(sx * cy * cz, cx * sy * cz, cx * cy * sz);
    return x.norm() - r_ - a_ * cx * cy * cz;
  }

 private:
  double r_, a_, k_;
};

}  // namespace dtsl::test
