// Analytic implicit functions with exact values and gradients for the polygonizer tests: sphere, torus,
// two separate spheres, and a genus-2 shape (two tori blended by a C2 smooth minimum). Hessians are
// central differences of the exact gradient (the polygonizers never use them; the interface asks for one).
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "framework/core/implicit.hpp"
#include "tests/support/analytic_implicit.hpp"

namespace dtsl::test {

class AnalyticImplicit : public CentralDifferenceImplicit {
 public:
  explicit AnalyticImplicit(double half_width = 1.5) : CentralDifferenceImplicit(half_width) {}

  /// Distance from x to the zero set: exact for signed distance functions, |f|/|grad f| (first order,
  /// accurate for the small distances of a polygonization) otherwise.
  virtual double distance(const Vec3& x) const {
    Vec3 g;
    const double v = eval(x, g);
    return std::abs(v) / g.norm();
  }
  virtual std::string name() const = 0;
  virtual int genus() const = 0;
  virtual int components() const = 0;
  /// Total area of the zero set (for "each component meshed once").
  virtual double area() const = 0;
};

/// |x - c| - r.
class Sphere final : public AnalyticImplicit {
 public:
  Sphere(const Vec3& c, double r) : c_(c), r_(r) {}
  double distance(const Vec3& x) const override { return std::abs((x - c_).norm() - r_); }
  std::string name() const override { return "sphere"; }
  int genus() const override { return 0; }
  int components() const override { return 1; }
  double area() const override { return 4.0 * M_PI * r_ * r_; }

 protected:
  double eval(const Vec3& x, Vec3& g) const override {
    const Vec3 d = x - c_;
    const double n = d.norm();
    g = n > 0 ? Vec3(d / n) : Vec3::UnitZ();
    return n - r_;
  }

 private:
  Vec3 c_;
  double r_;
};

/// Signed distance to the torus of radii R (centre circle, in the plane z = c.z) and r (tube).
class Torus final : public AnalyticImplicit {
 public:
  Torus(const Vec3& c, double R, double r) : c_(c), R_(R), r_(r) {}
  double distance(const Vec3& x) const override {
    Vec3 g;
    return std::abs(eval(x, g));
  }
  std::string name() const override { return "torus"; }
  int genus() const override { return 1; }
  int components() const override { return 1; }
  double area() const override { return 4.0 * M_PI * M_PI * R_ * r_; }
  static double sdf(const Vec3& x, const Vec3& c, double R, double r, Vec3& g) {
    const Vec3 d = x - c;
    const double q = std::hypot(d.x(), d.y());
    const Vec3 radial = q > 0 ? Vec3(d.x() / q, d.y() / q, 0) : Vec3::UnitX();
    const double a = q - R, b = d.z(), n = std::hypot(a, b);
    g = n > 0 ? Vec3((a * radial + b * Vec3::UnitZ()) / n) : Vec3::UnitZ();
    return n - r;
  }

 protected:
  double eval(const Vec3& x, Vec3& g) const override { return sdf(x, c_, R_, r_, g); }

 private:
  Vec3 c_;
  double R_, r_;
};

/// Two disjoint spheres: min of their signed distances (exact distance to the union's surface).
class TwoSpheres final : public AnalyticImplicit {
 public:
  TwoSpheres(const Vec3& c1, double r1, const Vec3& c2, double r2) : a_(c1, r1), b_(c2, r2) {}
  double distance(const Vec3& x) const override { return std::min(a_.distance(x), b_.distance(x)); }
  std::string name() const override { return "two_spheres"; }
  int genus() const override { return 0; }
  int components() const override { return 2; }
  double area() const override { return a_.area() + b_.area(); }
  const Sphere& first() const { return a_; }
  const Sphere& second() const { return b_; }

 protected:
  double eval(const Vec3& x, Vec3& g) const override {
    Vec3 ga, gb;
    const double va = a_.evaluate(x, &ga), vb = b_.evaluate(x, &gb);
    g = va <= vb ? ga : gb;
    return std::min(va, vb);
  }

 private:
  Sphere a_, b_;
};

/// Genus 2: two tori side by side (centres (+-0.6, 0, 0), R = 0.5, r = 0.2) whose tubes overlap near
/// the origin, joined by the cubic smooth minimum smin(a, b) = min(a, b) - k h^3 / 6,
/// h = max(k - |a - b|, 0) / k, which is C2 and has gradient (1 - h^2/2) grad a + (h^2/2) grad b for a <= b.
class DoubleTorus final : public AnalyticImplicit {
 public:
  std::string name() const override { return "double_torus"; }
  int genus() const override { return 2; }
  int components() const override { return 1; }
  double area() const override { return 2.0 * 4.0 * M_PI * M_PI * 0.5 * 0.2; }  // approximate (blend ignored)

 protected:
  double eval(const Vec3& x, Vec3& g) const override {
    Vec3 ga, gb;
    double a = Torus::sdf(x, Vec3(-0.6, 0, 0), 0.5, 0.2, ga);
    double b = Torus::sdf(x, Vec3(0.6, 0, 0), 0.5, 0.2, gb);
    if (b < a) {
      std::swap(a, b);
      std::swap(ga, gb);
    }
    const double k = 0.25, h = std::max(k - (b - a), 0.0) / k;
    g = (1.0 - 0.5 * h * h) * ga + 0.5 * h * h * gb;
    return a - k * h * h * h / 6.0;
  }
};

/// The plane z = 0 crossing the whole domain: a level set that is not closed inside it.
class Plane final : public AnalyticImplicit {
 public:
  std::string name() const override { return "plane"; }
  int genus() const override { return 0; }
  int components() const override { return 1; }
  double area() const override { return 9.0; }

 protected:
  double eval(const Vec3& x, Vec3& g) const override {
    g = Vec3::UnitZ();
    return x.z();
  }
};

/// The classical polynomial genus-2 surface: a tube around the lemniscate (x^2+y^2)^2 = x^2 - y^2,
/// f = g^2 + z^2 - r^2 with g = (x^2+y^2)^2 - x^2 + y^2, in coordinates scaled by `scale`. Far from a
/// distance function (|grad f| ranges over an order of magnitude on the surface) and thin (curvature
/// radius ~0.05 at the lobes' ends): a hard case for step control.
class PolynomialDoubleTorus final : public AnalyticImplicit {
 public:
  explicit PolynomialDoubleTorus(double r = 0.15, double scale = 1.4) : r_(r), s_(scale) {}
  std::string name() const override { return "polynomial_double_torus"; }
  int genus() const override { return 2; }
  int components() const override { return 1; }
  double area() const override { return 0.0; }  // unknown in closed form

 protected:
  double eval(const Vec3& p, Vec3& grad) const override {
    const Vec3 q = p / s_;
    const double x = q.x(), y = q.y(), z = q.z(), rho = x * x + y * y;
    const double g = rho * rho - x * x + y * y;
    const double gx = 4 * x * rho - 2 * x, gy = 4 * y * rho + 2 * y;
    grad = Vec3(2 * g * gx, 2 * g * gy, 2 * z) / s_;
    return g * g + z * z - r_ * r_;
  }

 private:
  double r_, s_;
};

/// A Phase-1-like level set: the uniform tensor-product cubic B-spline (the full-octree special case
/// of the T-spline, docs/design.md §1) quasi-interpolating another shape's function on a grid of spacing h
/// (c_ijk = g(node), O(h^2) off g). Piecewise polynomial and C2, with |grad f| != 1 away from the
/// source's zero set: what the polygonizers will see from the evolution, without linking it.
class BSplineLevelSet final : public AnalyticImplicit {
 public:
  BSplineLevelSet(std::unique_ptr<AnalyticImplicit> source, double h) : source_(std::move(source)), h_(h) {
    const BoundingBox d = domain();
    origin_ = d.min - Vec3::Constant(2 * h);
    n_ = static_cast<int>(std::ceil((d.max - d.min).maxCoeff() / h)) + 5;
    c_.resize(static_cast<std::size_t>(n_) * n_ * n_);
    for (int k = 0; k < n_; ++k)
      for (int j = 0; j < n_; ++j)
        for (int i = 0; i < n_; ++i) c_[index(i, j, k)] = source_->value(origin_ + h * Vec3(i, j, k));
  }
  std::string name() const override { return "bspline_" + source_->name(); }
  int genus() const override { return source_->genus(); }
  int components() const override { return source_->components(); }
  double area() const override { return source_->area(); }

 protected:
  double eval(const Vec3& x, Vec3& g) const override {
    const Vec3 t = (x - origin_) / h_;
    int base[3];
    double w[3][4], dw[3][4];
    for (int a = 0; a < 3; ++a) {
      base[a] = static_cast<int>(std::floor(t[a])) - 1;
      for (int s = 0; s < 4; ++s) {
        const double u = t[a] - (base[a] + s);
        w[a][s] = kernel(u);
        dw[a][s] = derivative(u) / h_;
      }
    }
    double v = 0.0;
    g.setZero();
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
          const int ii = std::clamp(base[0] + i, 0, n_ - 1), jj = std::clamp(base[1] + j, 0, n_ - 1),
                    kk = std::clamp(base[2] + k, 0, n_ - 1);
          const double c = c_[index(ii, jj, kk)];
          v += c * w[0][i] * w[1][j] * w[2][k];
          g += c * Vec3(dw[0][i] * w[1][j] * w[2][k], w[0][i] * dw[1][j] * w[2][k], w[0][i] * w[1][j] * dw[2][k]);
        }
    return v;
  }

 private:
  static double kernel(double u) {
    const double a = std::abs(u);
    if (a < 1) return (4 - 6 * a * a + 3 * a * a * a) / 6;
    if (a < 2) return (2 - a) * (2 - a) * (2 - a) / 6;
    return 0.0;
  }
  static double derivative(double u) {
    const double a = std::abs(u), s = u < 0 ? -1.0 : 1.0;
    if (a < 1) return -2 * u + 1.5 * u * a;
    if (a < 2) return -s * (2 - a) * (2 - a) / 2;
    return 0.0;
  }
  std::size_t index(int i, int j, int k) const { return (static_cast<std::size_t>(k) * n_ + j) * n_ + i; }

  std::unique_ptr<AnalyticImplicit> source_;
  double h_;
  Vec3 origin_;
  int n_ = 0;
  std::vector<double> c_;
};

/// `inner` moved by a rotation and a translation: f(x) = inner(R^T (x - t)); distances are preserved.
class Moved final : public AnalyticImplicit {
 public:
  Moved(std::unique_ptr<AnalyticImplicit> inner, const Mat3& rotation, const Vec3& translation)
      : inner_(std::move(inner)), r_(rotation), t_(translation) {}
  double distance(const Vec3& x) const override { return inner_->distance(r_.transpose() * (x - t_)); }
  std::string name() const override { return "moved_" + inner_->name(); }
  int genus() const override { return inner_->genus(); }
  int components() const override { return inner_->components(); }
  double area() const override { return inner_->area(); }

 protected:
  double eval(const Vec3& x, Vec3& g) const override {
    Vec3 gi;
    const double v = inner_->evaluate(r_.transpose() * (x - t_), &gi);
    g = r_ * gi;
    return v;
  }

 private:
  std::unique_ptr<AnalyticImplicit> inner_;
  Mat3 r_;
  Vec3 t_;
};

}  // namespace dtsl::test
