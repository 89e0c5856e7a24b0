// Analytic implicit functions with exact values and gradients for the polygonizer tests: sphere, torus,
// two separate spheres, and a genus-2 shape (two tori blended by a C2 smooth minimum). Hessians are
// central differences of the exact gradient (the polygonizers never use them; the interface asks for one).
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "framework/core/implicit.hpp"

namespace dtsl::test {

class AnalyticImplicit : public ImplicitFunction {
 public:
  explicit AnalyticImplicit(double half_width = 1.5) {
    box_.extend(Vec3::Constant(-half_width));
    box_.extend(Vec3::Constant(half_width));
  }
  double evaluate(const Vec3& x, Vec3* gradient = nullptr, Mat3* hessian = nullptr) const final {
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
    }
    return v;
  }
  BoundingBox domain() const final { return box_; }

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

 protected:
  virtual double eval(const Vec3& x, Vec3& g) const = 0;

 private:
  BoundingBox box_;
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
