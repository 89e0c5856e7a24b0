// The noise estimate reads the standard deviation of noise along the normal, and reads ~0 on clean
// curved samples (the quadric absorbs the curvature a plane fit would report as noise).
#include <catch2/catch.hpp>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>

#include "algorithms/displacement/noise_estimate.hpp"
#include "framework/core/error.hpp"
#include "tests/displacement/support.hpp"

using namespace dtsl;
using namespace dtsl::test;

namespace {

// A torus (R 0.6, r 0.25: curvature radii 0.25 to 0.85) sampled at n points, with isotropic Gaussian
// noise of standard deviation `noise` on every coordinate (as the `noise` corruption applies it).
std::vector<Vec3> noisy_torus(int n, double noise, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 2 * M_PI);
  std::normal_distribution<double> N(0.0, noise > 0 ? noise : 1.0);  // unused when noise is 0
  std::vector<Vec3> out;
  const double R = 0.6, r = 0.25;
  while (static_cast<int>(out.size()) < n) {
    const double a = U(rng), b = U(rng);
    // Area-uniform: accept b with probability (R + r cos b) / (R + r).
    if (std::uniform_real_distribution<double>(0, 1)(rng) > (R + r * std::cos(b)) / (R + r)) continue;
    Vec3 p((R + r * std::cos(b)) * std::cos(a), (R + r * std::cos(b)) * std::sin(a), r * std::sin(b));
    if (noise > 0) p += Vec3(N(rng), N(rng), N(rng));
    out.push_back(p);
  }
  return out;
}

}  // namespace

TEST_CASE("the noise estimate reads the noise's standard deviation along the normal", "[noise]") {
  for (double sigma : {0.001, 0.002, 0.005}) {
    const NoiseEstimate e = estimate_noise(noisy_torus(30000, sigma, 7));
    std::cout << "[noise] true " << sigma << " estimated " << e.sigma << " spacing " << e.spacing << "\n";
    CHECK(e.sigma > 0.85 * sigma);
    CHECK(e.sigma < 1.15 * sigma);
    CHECK(e.fitted_points > 3900);
  }
}

TEST_CASE("clean curved samples read far below the spacing, and below a plane fit's curvature error", "[noise]") {
  const std::vector<Vec3> clean = noisy_torus(30000, 0.0, 7);
  const NoiseEstimate e = estimate_noise(clean);
  // A plane through 20 neighbours on a radius-0.25 tube would leave ~ rho^2 / (2 r) with rho ~ 2 spacings.
  const double plane_error = std::pow(2 * e.spacing, 2) / (2 * 0.25);
  std::cout << "[noise] clean torus: estimated " << e.sigma << ", spacing " << e.spacing << ", plane-fit scale "
            << plane_error << "\n";
  CHECK(e.sigma < 0.1 * plane_error);
  CHECK(e.sigma < 1e-4);
}

TEST_CASE("a clean but sparse sample of a detailed shape does not read as noise", "[noise]") {
  // A sphere with relief of wavelength ~ 12 spacings (radius 0.6 + 0.01 sin(8 theta) cos(8 phi)),
  // 3000 points: a single-scale quadric fit reads the relief as noise; the two-scale extrapolation
  // separates it from real noise added on top.
  const auto relief = [](double noise, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> N(0.0, noise > 0 ? noise : 1.0);
    std::vector<Vec3> out;
    for (const Vec3& d : fibonacci_directions(3000)) {
      const double theta = std::acos(d.z()), phi = std::atan2(d.y(), d.x());
      Vec3 p = (0.6 + 0.01 * std::sin(8 * theta) * std::cos(8 * phi)) * d;
      if (noise > 0) p += Vec3(N(rng), N(rng), N(rng));
      out.push_back(p);
    }
    return out;
  };
  const NoiseEstimate clean = estimate_noise(relief(0.0, 1));
  const NoiseEstimate noisy = estimate_noise(relief(0.003, 1));
  std::cout << "[noise] clean relief: rms " << clean.rms_small << " / " << clean.rms_large << " -> " << clean.sigma
            << "; with noise 0.003: " << noisy.rms_small << " / " << noisy.rms_large << " -> " << noisy.sigma << "\n";
  CHECK(clean.rms_large > 0.8e-3);  // what a single fit of 24 neighbours would call noise
  CHECK(clean.sigma < 0.5 * clean.rms_large);
  CHECK(clean.sigma < 0.15 * noisy.sigma);
  CHECK(noisy.sigma > 0.75 * 0.003);
  CHECK(noisy.sigma < 1.3 * 0.003);
}

TEST_CASE("the noise estimate names bad input", "[noise]") {
  std::vector<Vec3> few(5, Vec3(0, 0, 0));
  CHECK_THROWS_WITH(estimate_noise(few), Catch::Contains("fewer than the 24 neighbours"));
  std::vector<Vec3> points = noisy_torus(100, 0.001, 1);
  points[42].x() = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(estimate_noise(points), Catch::Contains("point 42 is not finite"));
  NoiseEstimateOptions o;
  o.neighbours = 3;
  CHECK_THROWS_AS(estimate_noise(noisy_torus(100, 0.001, 1), o), ConfigError);
  o = NoiseEstimateOptions{};
  o.small_neighbours = o.neighbours;
  CHECK_THROWS_WITH(estimate_noise(noisy_torus(100, 0.001, 1), o), Catch::Contains("small_neighbours"));
  // Coincident points: no fit is possible, the estimate says so by fitting none rather than crashing.
  const NoiseEstimate same = estimate_noise(std::vector<Vec3>(50, Vec3(0.1, 0.2, 0.3)));
  CHECK(same.fitted_points == 0);
  CHECK(same.sigma == 0.0);
}
