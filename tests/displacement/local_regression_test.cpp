// Local polynomial regression reproduces the polynomials of its degree exactly (the equivalent kernel's
// defining property) and falls back to a lower degree where the samples cannot support the fit.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "algorithms/displacement/local_regression.hpp"

using namespace dtsl;

namespace {

struct Samples {
  std::vector<Vec3> positions;
  std::vector<std::pair<int, double>> taps;
};

// n samples scattered over the tangent plane of (v, normal) within radius r, Gaussian weights of width
// r / 3, each lifted off the plane a little (the feet lie on a curved surface, not on the plane).
Samples scatter(const Vec3& v, const Vec3& normal, int n, double r, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(-r, r);
  const Vec3 t1 = normal.unitOrthogonal(), t2 = normal.cross(t1);
  Samples s;
  while (static_cast<int>(s.positions.size()) < n) {
    const double a = U(rng), b = U(rng);
    if (a * a + b * b > r * r) continue;
    s.positions.push_back(v + a * t1 + b * t2 + 0.1 * (a * a + b * b) * normal);
    const double sigma = r / 3;
    s.taps.emplace_back(static_cast<int>(s.positions.size()) - 1, std::exp(-(a * a + b * b) / (2 * sigma * sigma)));
  }
  return s;
}

// sum_k l_k y(p_k) for y given in the tangent coordinates (u, w) of v's plane.
template <class F>
double apply(const Samples& s, const std::vector<std::pair<int, double>>& taps, const Vec3& v, const Vec3& normal, F y) {
  const Vec3 t1 = normal.unitOrthogonal(), t2 = normal.cross(t1);
  double sum = 0.0;
  for (const auto& [k, l] : taps) {
    const Vec3 d = s.positions[k] - v;
    sum += l * y(d.dot(t1), d.dot(t2));
  }
  return sum;
}

}  // namespace

TEST_CASE("local regression of degree p reproduces polynomials of degree p at the vertex", "[regression]") {
  const Vec3 v(0.3, -0.2, 0.5), normal = Vec3(1, 2, 2).normalized();
  const Samples s = scatter(v, normal, 60, 0.05, 3);
  const auto constant = [](double, double) { return 0.7; };
  const auto linear = [](double u, double w) { return 0.7 + 3 * u - 5 * w; };
  const auto quadratic = [](double u, double w) { return 0.7 + 3 * u - 5 * w + 40 * u * u - 25 * u * w + 60 * w * w; };
  for (int degree : {0, 1, 2}) {
    std::vector<std::pair<int, double>> taps = s.taps;
    REQUIRE(local_regression_weights(taps, s.positions, v, normal, 0.05 / 3, degree) == degree);
    double sum = 0.0;
    for (const auto& t : taps) sum += t.second;
    CHECK(sum == Approx(1.0).margin(1e-12));  // constants are reproduced at every degree
    CHECK(apply(s, taps, v, normal, constant) == Approx(0.7).margin(1e-12));
    if (degree >= 1) CHECK(apply(s, taps, v, normal, linear) == Approx(0.7).margin(1e-10));
    if (degree >= 2) CHECK(apply(s, taps, v, normal, quadratic) == Approx(0.7).margin(1e-10));
    // ... and not those of a higher degree (the samples are not symmetric about v).
    if (degree == 0) CHECK(std::abs(apply(s, taps, v, normal, linear) - 0.7) > 1e-4);
    if (degree == 1) CHECK(std::abs(apply(s, taps, v, normal, quadratic) - 0.7) > 1e-4);
  }
}

TEST_CASE("local regression falls back where the samples cannot support the degree", "[regression]") {
  const Vec3 v(0, 0, 0), normal(0, 0, 1);
  SECTION("too few samples for a quadratic, enough for a line") {
    Samples s = scatter(v, normal, 8, 0.05, 5);
    CHECK(local_regression_weights(s.taps, s.positions, v, normal, 0.02, 2) == 1);
  }
  SECTION("collinear samples cannot fix a plane: the mean") {
    Samples s;
    for (int i = 0; i < 30; ++i) {
      s.positions.emplace_back(-0.05 + 0.1 * i / 29.0, 0.0, 0.0);
      s.taps.emplace_back(i, 1.0 + 0.01 * i);
    }
    CHECK(local_regression_weights(s.taps, s.positions, v, normal, 0.02, 2) == 0);
    double sum = 0.0;
    for (const auto& t : s.taps) {
      sum += t.second;
      CHECK(t.second > 0);
    }
    CHECK(sum == Approx(1.0));
  }
}

TEST_CASE("the misfit of a degree-p fit is zero on polynomials of degree p and grows with a kink", "[regression]") {
  const Vec3 v(0.3, -0.2, 0.5), normal = Vec3(1, 2, 2).normalized();
  const double r = 0.05;
  const Samples s = scatter(v, normal, 80, r, 7);
  const Vec3 t1 = normal.unitOrthogonal(), t2 = normal.cross(t1);
  const auto values_of = [&](auto y) {
    std::vector<double> values;
    for (const Vec3& p : s.positions) values.push_back(y((p - v).dot(t1), (p - v).dot(t2)));
    return values;
  };
  const std::vector<double> linear = values_of([](double u, double w) { return 0.7 + 3 * u - 5 * w; });
  const std::vector<double> quadratic =
      values_of([](double u, double w) { return 0.7 + 3 * u - 5 * w + 40 * u * u - 25 * u * w + 60 * w * w; });
  CHECK(local_regression_misfit(s.taps, s.positions, linear, v, normal, r / 3, 1) < 1e-12);
  CHECK(local_regression_misfit(s.taps, s.positions, quadratic, v, normal, r / 3, 2) < 1e-12);
  CHECK(local_regression_misfit(s.taps, s.positions, quadratic, v, normal, r / 3, 1) > 1e-5);
  CHECK(local_regression_misfit(s.taps, s.positions, linear, v, normal, r / 3, 0) > 1e-3);
  // A crease through the samples: slope change s at u = a. The misfit is proportional to s.
  const auto crease = [&](double slope, double a) {
    return values_of([=](double u, double) { return 0.7 + 3 * u + slope * std::max(0.0, u - a); });
  };
  const double m1 = local_regression_misfit(s.taps, s.positions, crease(0.5, 0.005), v, normal, r / 3, 1);
  const double m2 = local_regression_misfit(s.taps, s.positions, crease(1.0, 0.005), v, normal, r / 3, 1);
  CHECK(m1 > 0.02 * (r / 3));
  CHECK(m2 == Approx(2 * m1).epsilon(1e-9));
  // Farther from v, less of the crease lies under the weights.
  CHECK(local_regression_misfit(s.taps, s.positions, crease(0.5, 0.03), v, normal, r / 3, 1) < m1);
  SECTION("too few samples for the degree: -1") {
    Samples few = scatter(v, normal, 8, r, 5);
    std::vector<double> values(few.positions.size(), 1.0);
    CHECK(local_regression_misfit(few.taps, few.positions, values, v, normal, r / 3, 2) == -1.0);
    CHECK(local_regression_misfit(few.taps, few.positions, values, v, normal, r / 3, 1) == Approx(0.0).margin(1e-12));
  }
}
