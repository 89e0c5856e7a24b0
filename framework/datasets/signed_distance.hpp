// Building blocks of the implicit shape families (private to framework/datasets): signed distances of
// simple solids (negative inside) and smooth Boolean operations. The smooth union and difference round
// every crease with a fillet of width `blend`, so the combined surface is a smooth (C2) manifold wherever
// the blended functions are, and a mesh of it has no sharp edge to misrepresent.
#pragma once

#include <algorithm>
#include <cmath>

#include "framework/core/types.hpp"

namespace dtsl::dataset_detail::sdf {

/// Smooth minimum (union): min(a, b) where |a - b| >= blend, rounded by a cubic fillet in between
/// (twice continuously differentiable). blend = 0 is the plain minimum.
inline double smooth_union(double a, double b, double blend) {
  if (blend <= 0.0) return std::min(a, b);
  const double h = std::max(blend - std::abs(a - b), 0.0) / blend;
  return std::min(a, b) - h * h * h * blend / 6.0;
}

/// Smooth difference: the solid of `a` minus the solid of `b`, creases rounded over `blend`.
inline double smooth_difference(double a, double b, double blend) { return -smooth_union(-a, b, blend); }

inline double sphere(const Vec3& p, const Vec3& centre, double radius) { return (p - centre).norm() - radius; }

/// A bar of radius `radius` around the segment [a, b] with hemispherical ends.
inline double capsule(const Vec3& p, const Vec3& a, const Vec3& b, double radius) {
  const Vec3 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm() - radius;
}

/// A ring torus around the z axis through `centre`.
inline double torus(const Vec3& p, const Vec3& centre, double R, double r) {
  const Vec3 q = p - centre;
  return std::hypot(std::hypot(q.x(), q.y()) - R, q.z()) - r;
}

/// Signed distance in the plane to the rectangle of half-sizes (a, b) centred at the origin with
/// corners rounded by `corner` (<= min(a, b)).
inline double rounded_rectangle(double x, double y, double a, double b, double corner) {
  const double qx = std::abs(x) - (a - corner), qy = std::abs(y) - (b - corner);
  return std::hypot(std::max(qx, 0.0), std::max(qy, 0.0)) + std::min(std::max(qx, qy), 0.0) - corner;
}

/// A box of half-sizes `half` centred at `centre`, its edges and corners rounded by `rounding`: the set
/// of points within `rounding` of the inner box (half - rounding), so its surface is smooth (C1).
inline double rounded_box(const Vec3& p, const Vec3& centre, const Vec3& half, double rounding) {
  const Vec3 q = (p - centre).cwiseAbs() - (half - Vec3::Constant(rounding));
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0) - rounding;
}

}  // namespace dtsl::dataset_detail::sdf
