// The product with a symmetric matrix stored as its lower triangle equals the product with the whole
// matrix, bit for bit the same for every thread count; conjugate gradients on it solve the system.
#include <catch2/catch.hpp>

#include <Eigen/SparseCholesky>
#include <random>
#include <stdexcept>
#include <vector>

#include "algorithms/evolution/conjugate_gradient.hpp"
#include "algorithms/evolution/normal_equations.hpp"
#include "algorithms/evolution/symmetric_product.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

using namespace dtsl;

namespace {

// A random SPD lower triangle: n unknowns, each coupled to up to `band` earlier ones at random offsets
// (some far, so that chunks reach rows far below their columns), diagonally dominant.
Eigen::SparseMatrix<double> random_spd_lower(int n, int band, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::uniform_int_distribution<int> offset(1, 4 * band);
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> row_sum(std::size_t(n), 0.0);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < band; ++k) {
      const int j = i - offset(rng);
      if (j < 0) continue;
      const double a = value(rng);
      entries.emplace_back(i, j, a);
      row_sum[std::size_t(i)] += std::abs(a), row_sum[std::size_t(j)] += std::abs(a);
    }
  for (int i = 0; i < n; ++i) entries.emplace_back(i, i, row_sum[std::size_t(i)] + 0.5);
  Eigen::SparseMatrix<double> lower(n, n);
  lower.setFromTriplets(entries.begin(), entries.end());  // sums duplicates, sorts, compresses
  return lower;
}

}  // namespace

TEST_CASE("symmetric product of the lower triangle equals the product with the whole matrix",
          "[evolution][solver]") {
  for (int n : {1, 7, 300, 5000}) {
    INFO("n = " << n);
    const Eigen::SparseMatrix<double> lower = random_spd_lower(n, 12, unsigned(n));
    const Eigen::SparseMatrix<double> full = lower.selfadjointView<Eigen::Lower>();
    const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0).array().sin();
    const Eigen::VectorXd expected = full * x;
    const SymmetricProduct product(lower);
    Eigen::VectorXd y;
    product.apply(x, y);
    REQUIRE(y.size() == n);
    CHECK((y - expected).norm() <= 1e-13 * (1.0 + expected.norm()));
  }
}

TEST_CASE("symmetric product: empty columns, and columns whose only entry is far below", "[evolution][solver]") {
  // Unknowns no row touches have empty columns (normal_equations.hpp); a chunk may end in them.
  const int n = 400;
  std::vector<Eigen::Triplet<double>> entries;
  for (int j = 0; j < n; ++j) {
    if (j % 7 == 3 || j > n - 30) continue;  // empty columns, a run of them at the end
    entries.emplace_back(j, j, 2.0 + j % 5);
    if (j + 150 < n) entries.emplace_back(j + 150, j, 0.25);
  }
  Eigen::SparseMatrix<double> lower(n, n);
  lower.setFromTriplets(entries.begin(), entries.end());
  lower.makeCompressed();
  const Eigen::SparseMatrix<double> full = lower.selfadjointView<Eigen::Lower>();
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(n, 1.0, 3.0);
  Eigen::VectorXd y;
  SymmetricProduct(lower).apply(x, y);
  const Eigen::VectorXd expected = full * x;
  CHECK((y - expected).norm() <= 1e-14 * expected.norm());
}

#ifdef _OPENMP
TEST_CASE("symmetric product and conjugate gradients: the same bits for any thread count", "[evolution][solver]") {
  const Eigen::SparseMatrix<double> lower = random_spd_lower(20000, 20, 3);
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(lower.rows(), 0.0, 50.0).array().cos();
  const int threads = omp_get_max_threads();
  const int dynamic = omp_get_dynamic();
  omp_set_dynamic(0);  // the team sizes asked for, so that the test compares what it says
  std::vector<Eigen::VectorXd> products, solutions;
  for (int t : {1, 2, 3, 16}) {
    omp_set_num_threads(t);
    int team = 0;
#pragma omp parallel
#pragma omp single
    team = omp_get_num_threads();
    INFO("threads asked " << t << ", team " << team);
    CHECK((team == t || t > omp_get_thread_limit()));
    Eigen::VectorXd y;
    SymmetricProduct(lower).apply(x, y);
    products.push_back(y);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(lower.rows());
    jacobi_conjugate_gradient(lower, x, 1e-10, 1000, u);
    solutions.push_back(u);
  }
  omp_set_num_threads(threads);
  omp_set_dynamic(dynamic);
  for (std::size_t k = 1; k < products.size(); ++k) {
    CHECK((products[0].array() == products[k].array()).all());
    CHECK((solutions[0].array() == solutions[k].array()).all());
  }
}
#endif

TEST_CASE("conjugate gradients solve an SPD system to the tolerance asked", "[evolution][solver]") {
  const Eigen::SparseMatrix<double> lower = random_spd_lower(3000, 15, 11);
  const Eigen::SparseMatrix<double> full = lower.selfadjointView<Eigen::Lower>();
  const Eigen::VectorXd g = Eigen::VectorXd::LinSpaced(lower.rows(), -3.0, 3.0);
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(full);
  const Eigen::VectorXd reference = ldlt.solve(g);
  SECTION("from zero, to 1e-4 and to 1e-10") {
    for (double tolerance : {1e-4, 1e-10}) {
      INFO("tolerance " << tolerance);
      Eigen::VectorXd u;  // empty: started from zero
      const ConjugateGradientResult r = jacobi_conjugate_gradient(lower, g, tolerance, 10000, u);
      CHECK(r.converged);
      CHECK(r.iterations > 0);
      CHECK(r.relative_residual <= tolerance);
      CHECK((full * u - g).norm() <= 2 * tolerance * g.norm());  // the recurrence's residual, not drifted far
      if (tolerance < 1e-8) CHECK((u - reference).norm() <= 1e-7 * reference.norm());
    }
  }
  SECTION("a warm start at the solution takes no iteration") {
    Eigen::VectorXd u = reference;
    const ConjugateGradientResult r = jacobi_conjugate_gradient(lower, g, 1e-6, 100, u);
    CHECK(r.iterations == 0);
    CHECK(r.converged);
  }
  SECTION("too few iterations: not converged, the residual said") {
    Eigen::VectorXd u;
    const ConjugateGradientResult r = jacobi_conjugate_gradient(lower, g, 1e-12, 2, u);
    CHECK(!r.converged);
    CHECK(r.iterations == 2);
    CHECK(r.relative_residual > 1e-12);
    CHECK(r.relative_residual == Approx((full * u - g).norm() / g.norm()).epsilon(1e-6));
  }
  SECTION("a zero right-hand side gives zero") {
    Eigen::VectorXd u = Eigen::VectorXd::Ones(lower.rows());
    const ConjugateGradientResult r =
        jacobi_conjugate_gradient(lower, Eigen::VectorXd::Zero(lower.rows()), 1e-6, 10, u);
    CHECK(r.converged);
    CHECK(u.isZero(0.0));
  }
}

TEST_CASE("symmetric product: a vector of the wrong size is rejected", "[evolution][solver][bad]") {
  const Eigen::SparseMatrix<double> lower = random_spd_lower(50, 3, 1);
  const SymmetricProduct product(lower);
  Eigen::VectorXd y;
  CHECK_THROWS_AS(product.apply(Eigen::VectorXd::Zero(49), y), std::invalid_argument);
  Eigen::SparseMatrix<double> uncompressed = lower;
  uncompressed.uncompress();
  CHECK_THROWS_AS(SymmetricProduct(uncompressed), std::invalid_argument);
  const Eigen::SparseMatrix<double> upper = Eigen::SparseMatrix<double>(lower.transpose());
  CHECK_THROWS_AS(SymmetricProduct(upper), std::invalid_argument);
}

TEST_CASE("conjugate gradients on a matrix that is not positive definite stop, not converged",
          "[evolution][solver][bad]") {
  std::vector<Eigen::Triplet<double>> entries{{0, 0, 1.0}, {1, 0, 1.0}, {1, 1, 1.0}};  // [[1, 1], [1, 1]]
  Eigen::SparseMatrix<double> lower(2, 2);
  lower.setFromTriplets(entries.begin(), entries.end());
  Eigen::VectorXd u;
  const ConjugateGradientResult r = jacobi_conjugate_gradient(lower, Eigen::Vector2d(1.0, -1.0), 1e-8, 10, u);
  CHECK(!r.converged);
  CHECK(u.allFinite());
}
