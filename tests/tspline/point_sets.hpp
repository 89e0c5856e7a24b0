// Synthetic point sets with known surfaces for the T-spline tests: uniform and strongly non-uniform
// samples, all inside [-1,1]^3 (the normalised frame of docs/design.md).
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "framework/core/types.hpp"

namespace dtsl::test {

/// `n` points uniformly on the sphere of radius r about c.
inline std::vector<Vec3> sphere_points(std::size_t n, double r, const Vec3& c, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  std::vector<Vec3> p;
  while (p.size() < n) {
    const Vec3 v(g(rng), g(rng), g(rng));
    if (v.norm() > 1e-12) p.push_back(c + r * v.normalized());
  }
  return p;
}

/// `n` points on the torus (major radius R, minor r, axis z) with a density growing as
/// exp(log(ratio) (x + R + r) / (2 (R + r))): `ratio` times denser at x = R + r than at x = -R - r.
/// A strongly non-uniform sample, so the adaptive T-mesh has levels side by side and T-junctions.
inline std::vector<Vec3> nonuniform_torus_points(std::size_t n, double R, double r, double ratio, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double pi = 3.14159265358979323846;
  std::vector<Vec3> p;
  while (p.size() < n) {
    const double a = 2 * pi * u(rng), b = 2 * pi * u(rng);
    // Area element of the torus is proportional to (R + r cos b): rejection-sample it, then density.
    if (u(rng) * (R + r) > R + r * std::cos(b)) continue;
    const Vec3 x((R + r * std::cos(b)) * std::cos(a), (R + r * std::cos(b)) * std::sin(a), r * std::sin(b));
    const double w = std::exp(std::log(ratio) * ((x.x() + R + r) / (2 * (R + r)) - 1.0));
    if (u(rng) > w) continue;
    p.push_back(x);
  }
  return p;
}

}  // namespace dtsl::test
