// The least-squares rows and their normal equations (least_squares_rows.hpp, normal_equations.hpp).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <random>

#include "algorithms/evolution/least_squares_rows.hpp"
#include "algorithms/evolution/normal_equations.hpp"
#include "algorithms/evolution/zero_set.hpp"
#include "algorithms/tspline/tspline.hpp"
#include "framework/core/error.hpp"
#include "tests/evolution/fixtures.hpp"

using namespace dtsl;

namespace {

Eigen::MatrixXd dense_rows(const LeastSquaresSystem& s) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(s.rows(), s.unknowns);
  for (int r = 0; r < s.rows(); ++r)
    for (int e = s.row_begin[r]; e < s.row_begin[r + 1]; ++e) A(r, s.column[e]) += s.value[e];
  return A;
}

}  // namespace

TEST_CASE("least squares: value and gradient rows are f' and its directional derivative", "[evolution][rows]") {
  auto basis = std::make_shared<TSplineBasis>(build_octree(test::sphere_data(800), test::test_options("distance", "eigen_ldlt").tmesh));
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> c(basis->size());
  for (double& x : c) x = u(rng);
  std::vector<Vec3> x;
  // In clusters of four: consecutive points in one leaf give rows with the same columns, which
  // finish() sorts with one permutation per run.
  for (int k = 0; k < 10; ++k) {
    const Vec3 centre(u(rng), u(rng), u(rng));
    for (int i = 0; i < 4; ++i) x.push_back(centre + 1e-3 * Vec3(u(rng), u(rng), u(rng)));
  }
  std::vector<Vec3> direction;
  for (std::size_t k = 0; k < x.size(); ++k) direction.push_back(Vec3(0.3, -0.2, 0.9) + 0.2 * Vec3(u(rng), u(rng), u(rng)));
  LeastSquaresBuilder rows(*basis);
  rows.add_value_rows(x, std::vector<double>(x.size(), 0.0), 2.0);
  rows.add_gradient_rows(x, direction, std::vector<double>(x.size(), 0.0), 4.0);
  const LeastSquaresSystem s = rows.finish(0.0);
  REQUIRE(s.rows() == 80);
  CHECK(s.value_rows == 40);
  CHECK(s.gradient_rows == 40);
  CHECK(s.smoothness_rows == 0);
  const Eigen::VectorXd cu = s.restrict(c);
  for (int k = 0; k < 40; ++k) {
    double value = 0, derivative = 0;
    for (int e = s.row_begin[k]; e < s.row_begin[k + 1]; ++e) value += s.value[e] * cu[s.column[e]];
    for (int e = s.row_begin[40 + k]; e < s.row_begin[41 + k]; ++e) derivative += s.value[e] * cu[s.column[e]];
    Vec3 g;
    CHECK(value == Approx(basis->evaluate(c.data(), x[k], &g)).margin(1e-12));
    CHECK(derivative == Approx(direction[k].dot(g)).margin(1e-10));
    for (int e = s.row_begin[k] + 1; e < s.row_begin[k + 1]; ++e) CHECK(s.column[e - 1] < s.column[e]);
  }
  // Weights: each kind's total weight spread evenly over its rows.
  CHECK(s.weight[0] == Approx(2.0 / 40));
  CHECK(s.weight[40] == Approx(4.0 / 40));
  // Unknowns are exactly the control points some row touches.
  std::vector<char> touched(basis->size(), 0);
  ActiveBasis active;
  for (const Vec3& p : x) {
    basis->active(p, active);
    for (int i : active.index) touched[i] = 1;
  }
  int count = 0;
  for (char t : touched) count += t;
  CHECK(s.unknowns == count);
  for (int k = 0; k < s.unknowns; ++k) CHECK(touched[s.control[k]]);
  const std::vector<double> full = s.expand(cu, basis->size());
  for (int i = 0; i < basis->size(); ++i) CHECK(full[i] == (touched[i] ? c[i] : 0.0));
  CHECK_THROWS_AS(LeastSquaresBuilder(*basis).finish(1.0), AlgorithmError);
}

TEST_CASE("least squares: held control points leave the rows, rows with none free are dropped, weights respread", "[evolution][rows]") {
  auto basis = std::make_shared<TSplineBasis>(build_octree(test::sphere_data(800), test::test_options("distance", "eigen_ldlt").tmesh));
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> c(basis->size());
  for (double& x : c) x = u(rng);
  // Two clusters far apart; only the control points of the first (all but one of them) are free.
  std::vector<Vec3> x;
  for (const Vec3 centre : {Vec3(-0.7, -0.6, -0.7), Vec3(0.7, 0.6, 0.7)})
    for (int i = 0; i < 6; ++i) x.push_back(centre + 0.05 * Vec3(u(rng), u(rng), u(rng)));
  std::vector<char> free(basis->size(), 0), second(basis->size(), 0);
  ActiveBasis active;
  for (int k = 0; k < 12; ++k) {
    basis->active(x[k], active);
    for (int i : active.index) (k < 6 ? free : second)[i] = 1;
  }
  for (int i = 0; i < basis->size(); ++i) REQUIRE(!(free[i] && second[i]));  // the clusters share no support
  basis->active(x[0], active);
  free[active.index[0]] = 0;  // one held control point inside the first cluster's support
  const std::vector<Vec3> direction(x.size(), Vec3(0.2, 0.5, -0.8));
  LeastSquaresBuilder rows(*basis);
  rows.add_value_rows(x, std::vector<double>(x.size(), 1.0), 1.0);
  rows.add_gradient_rows(x, direction, std::vector<double>(x.size(), 2.0), 3.0);
  CHECK(rows.rows_touching(free) == 12);
  const LeastSquaresSystem s = rows.finish(0.5, &free);
  CHECK(s.value_rows == 6);
  CHECK(s.gradient_rows == 6);
  CHECK(s.smoothness_rows == s.unknowns);
  int count = 0;
  for (char f : free) count += f;
  CHECK(s.unknowns == count);
  for (int k = 0; k < s.unknowns; ++k) CHECK(free[s.control[k]]);
  // Each kept row is the original row over the free control points, with its weight and target.
  const Eigen::VectorXd cu = s.restrict(c);
  for (int k = 0; k < 6; ++k) {
    Vec3 g;
    double value = 0.0, derivative = 0.0, expected_value = 0.0, expected_derivative = 0.0;
    basis->active(x[k], active);
    for (int e = 0; e < active.size(); ++e)
      if (free[active.index[e]]) {
        expected_value += active.value[e] * c[active.index[e]];
        expected_derivative += direction[k].dot(active.gradient[e]) * c[active.index[e]];
      }
    for (int e = s.row_begin[k]; e < s.row_begin[k + 1]; ++e) value += s.value[e] * cu[s.column[e]];
    for (int e = s.row_begin[6 + k]; e < s.row_begin[7 + k]; ++e) derivative += s.value[e] * cu[s.column[e]];
    CHECK(value == Approx(expected_value).margin(1e-12));
    CHECK(derivative == Approx(expected_derivative).margin(1e-10));
    CHECK(s.rhs[k] == 1.0);
    CHECK(s.rhs[6 + k] == 2.0);
    CHECK(s.weight[k] == Approx(1.0 / 6));  // each kind's weight spread over its 6 rows kept
    CHECK(s.weight[6 + k] == Approx(3.0 / 6));
  }
  // Bad flags: a wrong count, or nothing free that a row touches.
  LeastSquaresBuilder again(*basis);
  again.add_value_rows(x, std::vector<double>(x.size(), 1.0), 1.0);
  const std::vector<char> short_flags(std::size_t(basis->size() - 1), 1);
  CHECK_THROWS_AS(again.finish(0.0, &short_flags), AlgorithmError);
  LeastSquaresBuilder none(*basis);
  none.add_value_rows(x, std::vector<double>(x.size(), 1.0), 1.0);
  const std::vector<char> held(std::size_t(basis->size()), 0);
  CHECK(none.rows_touching(held) == 0);
  CHECK_THROWS_WITH(none.finish(0.0, &held), Catch::Contains("free control point"));
}

TEST_CASE("least squares: gradient rows from the band's site cache equal rows computed afresh, step after step",
          "[evolution][rows]") {
  auto basis = std::make_shared<TSplineBasis>(build_octree(test::sphere_data(800), test::test_options("distance", "eigen_ldlt").tmesh));
  const TSpline f = quasi_interpolant(basis, [](const Vec3& x) { return x.norm() - 0.7; });
  ZeroSetSampling sampling;
  sampling.band_subdivision = 2;
  sampling.band_width = 2.0;
  const ZeroSetSamples samples = sample_zero_set(f, basis->octree(), sampling);
  REQUIRE(samples.band_site.size() == samples.band.size());
  int sites = 0, zero_set = 0;
  for (int s : samples.band_site) (s >= 0 ? sites : zero_set) += 1;
  REQUIRE(sites > 100);
  REQUIRE(zero_set > 10);  // the zero-set points among the band: no site, computed afresh
  // Rows built through `cache` against rows computed afresh, for one "step" (the band, new directions).
  const auto same_rows = [&](GradientCache& cache, const std::vector<Vec3>& direction) {
    const std::vector<double> target(samples.band.size(), 0.5);
    LeastSquaresBuilder fresh(*basis), cached(*basis);
    fresh.add_gradient_rows(samples.band, direction, target, 1.0);
    cached.add_gradient_rows(samples.band, direction, target, 1.0, samples.band_site, cache);
    const LeastSquaresSystem a = fresh.finish(0.1), b = cached.finish(0.1);
    CHECK(a.row_begin == b.row_begin);
    CHECK(a.column == b.column);
    CHECK(a.value == b.value);  // bit for bit
    CHECK(a.control == b.control);
  };
  GradientCache cache(*basis, basis->octree().leaf_count() * 8);
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // Two steps: the second reads every site from the cache.
  for (int step = 0; step < 2; ++step) {
    std::vector<Vec3> direction;
    for (std::size_t m = 0; m < samples.band.size(); ++m) direction.push_back(Vec3(u(rng), u(rng), u(rng)));
    same_rows(cache, direction);
    CHECK(cache.filled() == std::size_t(sites));
  }
  // A cache over its memory budget keeps what fits and computes the rest afresh: the same rows.
  GradientCache tight(*basis, basis->octree().leaf_count() * 8, 20000);
  for (int step = 0; step < 2; ++step) {
    same_rows(tight, std::vector<Vec3>(samples.band.size(), Vec3(0.2, 0.5, -0.3)));
    CHECK(tight.bytes() <= 20000);
    CHECK(tight.filled() > 0);
    CHECK(tight.filled() < std::size_t(sites));
  }
  // A cache of another basis, or a site out of its range, is an error, not a wrong row.
  auto other = std::make_shared<TSplineBasis>(build_octree(test::sphere_data(300), test::test_options("distance", "eigen_ldlt").tmesh));
  GradientCache wrong(*other, 8 * other->octree().leaf_count());
  const std::vector<Vec3> direction(samples.band.size(), Vec3::UnitX());
  const std::vector<double> target(samples.band.size(), 0.0);
  LeastSquaresBuilder rows(*basis);
  CHECK_THROWS_AS(rows.add_gradient_rows(samples.band, direction, target, 1.0, samples.band_site, wrong), AlgorithmError);
  GradientCache small(*basis, 1);
  CHECK_THROWS_AS(rows.add_gradient_rows(samples.band, direction, target, 1.0, samples.band_site, small), AlgorithmError);
}

TEST_CASE("least squares: one Tikhonov row per unknown, weight spread over them", "[evolution][rows]") {
  const EvolutionOptions o = test::test_options("distance", "eigen_ldlt");
  const LeastSquaresSystem s = test::step_system(test::sphere_data(800), o);
  REQUIRE(s.unknowns > 0);
  CHECK(s.smoothness_rows == s.unknowns);
  for (int k = 0; k < s.smoothness_rows; ++k) {
    const int r = s.rows() - s.smoothness_rows + k;
    CHECK(s.row_begin[r + 1] - s.row_begin[r] == 1);
    CHECK(s.column[s.row_begin[r]] == k);
    CHECK(s.value[s.row_begin[r]] == 1.0);
    CHECK(s.rhs[r] == 0.0);
    CHECK(s.weight[r] == Approx(o.w_smooth / s.unknowns));
  }
}

TEST_CASE("normal equations equal A^T W A and A^T W b", "[evolution][rows]") {
  const EvolutionOptions o = test::test_options("distance", "eigen_ldlt");
  {
    const LeastSquaresSystem s = test::step_system(test::sphere_data(600), o);
    const Eigen::MatrixXd A = dense_rows(s);
    const Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(s.weight.data(), s.rows());
    const Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(s.rhs.data(), s.rows());
    const Eigen::MatrixXd N = A.transpose() * w.asDiagonal() * A;
    const Eigen::VectorXd g = A.transpose() * (w.asDiagonal() * b);
    const NormalEquations ne = normal_equations(s);
    const Eigen::MatrixXd lower = Eigen::MatrixXd(ne.lower);
    const Eigen::MatrixXd expected = N.triangularView<Eigen::Lower>();
    CHECK((lower - expected).cwiseAbs().maxCoeff() <= 1e-12 * N.cwiseAbs().maxCoeff());
    CHECK((ne.rhs - g).norm() <= 1e-12 * g.norm());
    // The objective and its gradient agree with the dense forms.
    const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(s.unknowns, -0.3, 0.4);
    CHECK(s.objective(u) == Approx((w.array() * (A * u - b).array().square()).sum()));
    CHECK((s.normal_residual(u) - (N * u - g)).norm() <= 1e-10 * g.norm());
  }
}

TEST_CASE("normal equations: runs of rows with the same columns, single entries and empty rows", "[evolution][rows]") {
  // normal_equations() sums each run of rows sharing columns before scattering it: runs of every
  // length, patterns that repeat after a break, and degenerate rows must all give A^T W A exactly.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::vector<std::vector<int>> patterns = {{0, 2, 5, 7}, {1, 2, 3}, {4}, {}, {0, 1, 2, 3, 4, 5, 6, 7}};
  LeastSquaresSystem s;
  s.unknowns = 8;
  for (int run = 0; run < 30; ++run) {
    const std::vector<int>& columns = patterns[std::size_t(run * 7 % 5)];
    const int length = 1 + run % 6;
    for (int r = 0; r < length; ++r) {
      for (int c : columns) {
        s.column.push_back(c);
        s.value.push_back(u(rng));
      }
      s.row_begin.push_back(int(s.column.size()));
      s.rhs.push_back(u(rng));
      s.weight.push_back(0.5 + 0.5 * u(rng));
    }
  }
  const Eigen::MatrixXd A = dense_rows(s);
  const Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(s.weight.data(), s.rows());
  const Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(s.rhs.data(), s.rows());
  const Eigen::MatrixXd N = A.transpose() * w.asDiagonal() * A;
  const NormalEquations ne = normal_equations(s);
  const Eigen::MatrixXd lower = Eigen::MatrixXd(ne.lower);
  CHECK((lower - Eigen::MatrixXd(N.triangularView<Eigen::Lower>())).cwiseAbs().maxCoeff() <= 1e-12 * N.cwiseAbs().maxCoeff());
  CHECK((ne.rhs - A.transpose() * (w.asDiagonal() * b)).norm() <= 1e-12 * ne.rhs.norm());
}
