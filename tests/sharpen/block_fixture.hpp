// The CAD-like test case of the sharpening phase: the `block` dataset shape (box with a cylindrical
// through-hole, sharp edges), points sampled on it, and a rounded starting mesh that looks like a
// displaced mesh: exact on the faces, rounded with radius `rounding` along every sharp edge. The
// rounded mesh is the marching-cubes mesh of a rounded-block distance function (a rounded box,
// intersected with the outside of the hole through a circular fillet).
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "algorithms/polygonize/marching_cubes.hpp"
#include "framework/core/implicit.hpp"
#include "framework/core/sampling.hpp"
#include "framework/datasets/dataset.hpp"

namespace dtsl::sharpen_test {

// The block shape's default dimensions (framework/datasets/block.cpp): 2 x 1.4 x 0.8, hole radius 0.35.
constexpr double kA = 1.0, kB = 0.7, kH = 0.4, kR = 0.35;

inline TriangleMesh block_truth() {
  register_dataset_plugins();
  auto source = shape_sources().create("block", "test");
  return *source->load().mesh;
}

inline std::vector<Vec3> block_points(const TriangleMesh& truth, std::size_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Vec3> pts;
  for (const auto& s : sample_surface(truth, count, rng)) pts.push_back(s.point);
  return pts;
}

/// Distance of x to the nearest sharp edge of the block: the 12 box edges and the 2 hole rims.
inline double distance_to_block_edges(const Vec3& x) {
  double best = HUGE_VAL;
  const double half[3] = {kA, kB, kH};
  for (int axis = 0; axis < 3; ++axis) {  // edges parallel to `axis`
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    for (int su : {-1, 1})
      for (int sw : {-1, 1}) {
        Vec3 p = x;
        p[axis] = std::clamp(x[axis], -half[axis], half[axis]);
        p[u] = su * half[u];
        p[w] = sw * half[w];
        best = std::min(best, (x - p).norm());
      }
  }
  const double rxy = std::hypot(x.x(), x.y());
  for (int s : {-1, 1}) best = std::min(best, std::hypot(rxy - kR, x.z() - s * kH));
  return best;
}

/// Points along the block's sharp edges (box edges and hole rims), about `spacing` apart.
inline std::vector<Vec3> block_edge_points(double spacing) {
  std::vector<Vec3> out;
  const double half[3] = {kA, kB, kH};
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    const int n = static_cast<int>(std::ceil(2 * half[axis] / spacing));
    for (int su : {-1, 1})
      for (int sw : {-1, 1})
        for (int i = 0; i <= n; ++i) {
          Vec3 p;
          p[axis] = -half[axis] + 2 * half[axis] * i / n;
          p[u] = su * half[u];
          p[w] = sw * half[w];
          out.push_back(p);
        }
  }
  const int n = static_cast<int>(std::ceil(2 * M_PI * kR / spacing));
  for (int s : {-1, 1})
    for (int i = 0; i < n; ++i) {
      const double phi = 2 * M_PI * i / n;
      out.emplace_back(kR * std::cos(phi), kR * std::sin(phi), s * kH);
    }
  return out;
}

/// The block with every sharp edge rounded with radius `rounding` (a signed distance away from the
/// edges; negative inside). Gradient by central differences.
class RoundedBlock final : public ImplicitFunction {
 public:
  explicit RoundedBlock(double rounding) : rho_(rounding) {}
  double evaluate(const Vec3& x, Vec3* gradient, Mat3* hessian) const override {
    if (gradient) {
      const double e = 1e-6;
      for (int i = 0; i < 3; ++i) {
        Vec3 a = x, b = x;
        a[i] += e;
        b[i] -= e;
        (*gradient)[i] = (value_at(a) - value_at(b)) / (2 * e);
      }
    }
    if (hessian) hessian->setZero();
    return value_at(x);
  }
  BoundingBox domain() const override {
    BoundingBox b;
    b.extend(Vec3(-1.23, -0.93, -0.63));
    b.extend(Vec3(1.21, 0.91, 0.61));
    return b;
  }

 private:
  double value_at(const Vec3& x) const {
    const Vec3 q = x.cwiseAbs() - Vec3(kA - rho_, kB - rho_, kH - rho_);
    const double box = q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0) - rho_;
    const double outside_hole = kR - std::hypot(x.x(), x.y());
    // Round intersection (a circular fillet of radius rho between the two surfaces).
    const double u0 = std::max(rho_ + box, 0.0), u1 = std::max(rho_ + outside_hole, 0.0);
    return std::min(-rho_, std::max(box, outside_hole)) + std::hypot(u0, u1);
  }
  double rho_;
};

inline TriangleMesh rounded_block_mesh(double rounding, double step) {
  RoundedBlock f(rounding);
  MarchingCubesOptions o;
  o.step = step;
  return marching_cubes(f, {}, o).mesh;
}

}  // namespace dtsl::sharpen_test
