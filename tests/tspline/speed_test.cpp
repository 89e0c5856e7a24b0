// Timings of T-mesh construction and T-spline evaluation. Hidden from the default run (tag [.]):
// `test_tspline "[speed]"` prints them. CPU time of this thread, so that other load on a shared machine
// inflates the numbers less than wall-clock time would. What is timed is also checked: the three
// evaluation orders give the same value, the order of the queries changes no value, the active basis is
// a partition of unity, and the quasi-interpolant of a sphere's distance is close to it near the data.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <iostream>

#include "algorithms/tspline/tspline.hpp"
#include "tests/tspline/fixtures.hpp"

using namespace dtsl;

namespace {
double cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}
}  // namespace

TEST_CASE("speed: T-mesh construction and evaluation at 1e6 points", "[.][speed]") {
  const auto points = test::nonuniform_torus_points(26000, 0.6, 0.25, 30.0, 1);
  for (int ppc : {16, 64}) {
    TMeshOptions o;
    o.points_per_cell = ppc;
    double t0 = cpu_seconds();
    Octree tree = build_octree(points, o);
    const double t_octree = cpu_seconds() - t0;
    t0 = cpu_seconds();
    auto basis = std::make_shared<TSplineBasis>(std::move(tree));
    const double t_basis = cpu_seconds() - t0;
    const auto st = basis->stats();
    std::cout << "26k points, depth 6, points_per_cell " << ppc << ": " << st.leaves << " leaves, "
              << st.control_points << " control points, mean support " << st.mean_support << " (max "
              << st.max_support << "); octree " << t_octree * 1e3 << " ms, knots + support lists "
              << t_basis * 1e3 << " ms (CPU, up to 2 OpenMP threads for the knots)\n";

    const TSpline f = quasi_interpolant(basis, [](const Vec3& x) { return x.norm() - 0.5; });
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-1.25, 1.25);
    std::vector<Vec3> random(1000000);
    for (Vec3& x : random) x = Vec3(u(rng), u(rng), u(rng));
    std::vector<Vec3> near(random.size());
    for (Vec3& x : near) x = points[rng() % points.size()] + 0.05 * Vec3(u(rng), u(rng), u(rng));
    std::vector<Vec3> coherent = near;  // the same points in leaf order: Newton / marching access pattern
    std::sort(coherent.begin(), coherent.end(),
              [&](const Vec3& a, const Vec3& b) { return basis->octree().locate(a) < basis->octree().locate(b); });
    double sink = 0;
    double value_sum[3] = {0, 0, 0};  // sum of f over the last timed set, per derivative order
    auto time = [&](const std::vector<Vec3>& q, int order) {
      const double s = cpu_seconds();
      Vec3 g;
      Mat3 h;
      double sum = 0;
      for (const Vec3& x : q) {
        sum += order == 0 ? f.evaluate(x) : order == 1 ? f.evaluate(x, &g) : f.evaluate(x, &g, &h);
        sink += order > 0 ? g.x() : 0.0;
      }
      const double seconds = cpu_seconds() - s;
      value_sum[order] = sum;
      sink += sum;
      return seconds / q.size() * 1e9;
    };
    // The same value whatever the order of derivatives asked for, and whatever the query order.
    auto check_orders_agree = [&](double reference) {
      for (const double v : value_sum) CHECK(v == Approx(reference).epsilon(1e-9).margin(1e-6));
    };
    std::cout << "  ns per evaluation (f / f+grad / f+grad+Hessian):\n"
              << "    1e6 random points in the domain, random order: " << time(random, 0) << " / "
              << time(random, 1) << " / " << time(random, 2) << "\n"
              << "    1e6 points near the data, random order:        " << time(near, 0) << " / " << time(near, 1)
              << " / " << time(near, 2) << "\n";
    const double near_sum = value_sum[0];
    check_orders_agree(near_sum);
    std::cout << "    the same points in leaf order:                 " << time(coherent, 0) << " / "
              << time(coherent, 1) << " / " << time(coherent, 2) << "\n";
    check_orders_agree(near_sum);
    ActiveBasis active;
    const double s = cpu_seconds();
    long n = 0;
    double worst_unity = 0;
    for (std::size_t k = 0; k < 200000; ++k) {
      basis->active(coherent[k * 5], active);
      n += active.size();
      double unity = 0;
      for (const double r : active.value) unity += r;
      worst_unity = std::max(worst_unity, std::abs(unity - 1.0));
    }
    std::cout << "    active basis (R_i, grad R_i), leaf order: " << (cpu_seconds() - s) / 200000 * 1e9
              << " ns, " << double(n) / 200000 << " functions on average\n";
    CHECK(std::isfinite(sink));
    CHECK(n > 0);
    CHECK(worst_unity < 1e-9);  // rational basis functions sum to one
    // A quasi-interpolant reproduces the sphere's distance near the data up to the cells' size.
    double worst = 0;
    for (std::size_t k = 0; k < 1000; ++k) worst = std::max(worst, std::abs(f.evaluate(near[k]) - (near[k].norm() - 0.5)));
    CHECK(worst < 0.05);
  }
}
