// The univariate cubic B-spline: its piecewise form against the Cox–de Boor recursion, and the
// properties the T-spline relies on (C2 at simple knots, partition of unity on a uniform knot row).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "algorithms/tspline/bspline.hpp"

using namespace dtsl;

namespace {
KnotValues random_knots(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> gap(0.05, 1.0), start(-2.0, 2.0);
  KnotValues t;
  t[0] = start(rng);
  for (int k = 1; k < 5; ++k) t[k] = t[k - 1] + gap(rng);
  return t;
}
}  // namespace

TEST_CASE("cubic B-spline pieces agree with the Cox-de Boor recursion", "[tspline][bspline]") {
  std::mt19937_64 rng(1);
  for (int trial = 0; trial < 200; ++trial) {
    const KnotValues t = random_knots(rng);
    const CubicBSpline n(t);
    std::uniform_real_distribution<double> u(t[0] - 0.5, t[4] + 0.5);
    for (int k = 0; k < 50; ++k) {
      const double x = u(rng);
      double v, d1, d2;
      n.evaluate<2>(x, v, d1, d2);
      const double scale = 1.0 / std::pow(std::min({t[1] - t[0], t[2] - t[1], t[3] - t[2], t[4] - t[3]}), 2);
      CHECK(v == Approx(cox_de_boor(t, x, 0)).margin(1e-12));
      CHECK(d1 == Approx(cox_de_boor(t, x, 1)).margin(1e-11 * scale));
      CHECK(d2 == Approx(cox_de_boor(t, x, 2)).margin(1e-11 * scale));
      CHECK(v >= -1e-15);
    }
  }
}

TEST_CASE("cubic B-spline is C2 at its knots and vanishes to second order at its ends", "[tspline][bspline]") {
  std::mt19937_64 rng(2);
  for (int trial = 0; trial < 100; ++trial) {
    const KnotValues t = random_knots(rng);
    const CubicBSpline n(t);
    // One-sided values at t_k -+ h: for a C2 function the jumps of N, N', N'' shrink like h; a jump
    // (a discontinuity of that order) would stay. Compare h = 1e-4 and 1e-6.
    for (int k = 0; k < 5; ++k) {
      double jump[2][3];
      for (int j = 0; j < 2; ++j) {
        const double h = j == 0 ? 1e-4 : 1e-6;
        double l[3], r[3];
        n.evaluate<2>(t[k] - h, l[0], l[1], l[2]);
        n.evaluate<2>(t[k] + h, r[0], r[1], r[2]);
        for (int d = 0; d < 3; ++d) jump[j][d] = std::abs(r[d] - l[d]);
      }
      for (int d = 0; d < 3; ++d) CHECK(jump[1][d] <= 0.02 * jump[0][d] + 1e-9);
    }
    CHECK(n.value(t[0]) == 0.0);
    CHECK(n.value(t[4]) == 0.0);
    double v = 1, d1 = 1, d2 = 1;
    n.evaluate<2>(1e300, v, d1, d2);  // far outside: exact zeros, no inf * 0
    CHECK((v == 0.0 && d1 == 0.0 && d2 == 0.0));
    n.evaluate<2>(std::nan(""), v, d1, d2);
    CHECK((v == 0.0 && d1 == 0.0 && d2 == 0.0));
    CHECK(n.greville() == Approx((t[1] + t[2] + t[3]) / 3.0));
  }
}

TEST_CASE("uniform cubic B-splines form a partition of unity and reproduce linear functions",
          "[tspline][bspline]") {
  // B-splines centred at the integers -1..5 cover [1, 3] completely.
  std::vector<CubicBSpline> row;
  for (int c = -1; c <= 5; ++c) row.emplace_back(KnotValues{c - 2.0, c - 1.0, double(c), c + 1.0, c + 2.0});
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(1.0, 3.0);
  for (int k = 0; k < 200; ++k) {
    const double x = u(rng);
    double sum = 0, first = 0, moment = 0;
    for (const CubicBSpline& n : row) {
      double v, d1, d2;
      n.evaluate<1>(x, v, d1, d2);
      sum += v;
      first += d1;
      moment += n.greville() * v;
    }
    CHECK(sum == Approx(1.0).margin(1e-14));
    CHECK(first == Approx(0.0).margin(1e-13));
    CHECK(moment == Approx(x).margin(1e-13));
  }
}

TEST_CASE("cubic B-spline rejects knots that do not strictly increase", "[tspline][bspline]") {
  CHECK_THROWS_AS(CubicBSpline(KnotValues{0, 1, 1, 2, 3}), AlgorithmError);
  CHECK_THROWS_AS(CubicBSpline(KnotValues{0, 1, 2, 4, 3}), AlgorithmError);
  CHECK_THROWS_WITH(CubicBSpline(KnotValues{0, 1, 2, 3, 3}), Catch::Contains("strictly increase"));
}
