// The rational T-spline f = sum c_i B_i / sum B_i on the adaptive T-meshes (with T-junctions) and the
// uniform grid: fast evaluation against the definition, partition of unity, positive denominator,
// derivatives against finite differences, C2 across faces (T-junction faces included), linear
// reproduction, quasi-interpolation of a sphere.
#include <catch2/catch.hpp>

#include <cmath>
#include <thread>

#include "algorithms/tspline/tspline.hpp"
#include "tests/tspline/fixtures.hpp"

using namespace dtsl;

namespace {

/// The definition, summed over every control point with the Cox–de Boor recursion: independent of
/// the support lists, the knot-vector tables and the piecewise B-spline form.
double brute_force(const TSplineBasis& basis, const std::vector<double>& c, const Vec3& x, double* denominator = nullptr) {
  double s0 = 0, s1 = 0;
  for (int i = 0; i < basis.size(); ++i) {
    const double b = basis.blending(i, x);
    s0 += b;
    s1 += c[i] * b;
  }
  if (denominator) *denominator = s0;
  return s1 / s0;
}

double max_abs(const Mat3& m) { return m.cwiseAbs().maxCoeff(); }

}  // namespace

TEST_CASE("fast evaluation equals the definition summed over all control points", "[tspline][eval]") {
  for (const auto& [name, basis] : test::all_bases()) {
    SECTION(name) {
      const std::vector<double> c = test::random_coefficients(*basis, 11);
      for (const Vec3& x : test::random_points(basis->domain(), 150, 12)) {
        double s0;
        const double expected = brute_force(*basis, c, x, &s0);
        INFO("x = " << x.transpose());
        CHECK(s0 > 0.0);
        CHECK(basis->evaluate(c.data(), x) == Approx(expected).margin(1e-12));
      }
    }
  }
}

TEST_CASE("partition of unity and a positive denominator everywhere in the domain", "[tspline][eval]") {
  for (const auto& [name, basis] : test::all_bases()) {
    SECTION(name) {
      ActiveBasis active;
      double min_denominator = 1e300;
      const std::vector<double> ones(basis->size(), 1.0);
      for (const Vec3& x : test::random_points(basis->domain(), 20000, 13)) {
        basis->active(x, active, true);
        double sum = 0;
        Vec3 grad = Vec3::Zero();
        Mat3 hess = Mat3::Zero();
        for (int k = 0; k < active.size(); ++k) {
          CHECK(active.value[k] > 0.0);
          sum += active.value[k];
          grad += active.gradient[k];
          hess += active.hessian[k];
        }
        min_denominator = std::min(min_denominator, active.denominator);
        const double scale = 1.0 / basis->octree().leaf_side(active.leaf);  // derivatives scale with 1/h
        CHECK(sum == Approx(1.0).margin(1e-13));
        CHECK(grad.norm() <= 1e-12 * scale);
        CHECK(max_abs(hess) <= 1e-11 * scale * scale);
        Vec3 g;
        CHECK(basis->evaluate(ones.data(), x, &g) == Approx(1.0).margin(1e-13));  // constants reproduced
        CHECK(g.norm() <= 1e-12 * scale);
      }
      INFO("smallest sum of blending functions " << min_denominator);
      CHECK(min_denominator > 0.0);
    }
  }
}

TEST_CASE("active basis reproduces f, grad f and the Hessian", "[tspline][eval]") {
  for (const auto& [name, basis] : test::all_bases()) {
    SECTION(name) {
      const std::vector<double> c = test::random_coefficients(*basis, 14);
      ActiveBasis active;
      for (const Vec3& x : test::random_points(basis->domain(), 500, 15)) {
        Vec3 g;
        Mat3 h;
        const double f = basis->evaluate(c.data(), x, &g, &h);
        basis->active(x, active, true);
        double fa = 0;
        Vec3 ga = Vec3::Zero();
        Mat3 ha = Mat3::Zero();
        for (int k = 0; k < active.size(); ++k) {
          fa += c[active.index[k]] * active.value[k];
          ga += c[active.index[k]] * active.gradient[k];
          ha += c[active.index[k]] * active.hessian[k];
        }
        CHECK(fa == Approx(f).margin(1e-12));
        CHECK((ga - g).norm() <= 1e-10 * std::max(1.0, g.norm()));
        CHECK(max_abs(ha - h) <= 1e-9 * std::max(1.0, max_abs(h)));
      }
    }
  }
}

TEST_CASE("gradient and Hessian agree with central finite differences", "[tspline][eval]") {
  for (const auto& [name, basis] : test::all_bases()) {
    SECTION(name) {
      const std::vector<double> c = test::random_coefficients(*basis, 16);
      BoundingBox inner = basis->domain();  // keep x +- h inside the domain (clamping would cut f)
      inner.min.array() += 1e-3;
      inner.max.array() -= 1e-3;
      const double h = 1e-6;
      for (const Vec3& x : test::random_points(inner, 500, 17)) {
        Vec3 g;
        Mat3 H;
        basis->evaluate(c.data(), x, &g, &H);
        Vec3 g_fd;
        Mat3 H_fd;
        for (int a = 0; a < 3; ++a) {
          Vec3 e = Vec3::Zero();
          e[a] = h;
          Vec3 gp, gm;
          const double fp = basis->evaluate(c.data(), x + e, &gp);
          const double fm = basis->evaluate(c.data(), x - e, &gm);
          g_fd[a] = (fp - fm) / (2 * h);
          H_fd.col(a) = (gp - gm) / (2 * h);
        }
        INFO("x = " << x.transpose() << "\ngrad " << g.transpose() << "\nfd   " << g_fd.transpose());
        // Truncation error ~ h |f'''| even across knot planes (f is C2); relative 1e-3 is generous.
        CHECK((g - g_fd).norm() <= 1e-3 * std::max(1.0, g.norm()));
        CHECK(max_abs(H - H_fd) <= 1e-3 * std::max(1.0, max_abs(H)));
        CHECK((H - H.transpose()).norm() == 0.0);
      }
    }
  }
}

TEST_CASE("f is C2 across cell faces, faces with T-junctions included", "[tspline][continuity]") {
  // One-sided values at x -+ h n on a face: the jumps of f, grad f and the Hessian shrink like h for
  // a C2 function; a missing or spurious blending function in a leaf's support list would leave a jump
  // that does not shrink. Random coefficients, so nothing cancels by symmetry.
  for (const auto& [name, basis] : test::all_bases()) {
    SECTION(name) {
      const Octree& t = basis->octree();
      const std::vector<double> c = test::random_coefficients(*basis, 18);
      std::vector<std::pair<int, int>> faces = test::t_junction_faces(t);
      const bool adaptive = !faces.empty();
      CHECK(adaptive == (basis != test::uniform_basis()));
      for (int l = 0; l < t.leaf_count(); l += 13) faces.emplace_back(l, l % 3);  // ordinary faces too
      std::mt19937_64 rng(19);
      std::uniform_real_distribution<double> u(0.0, 1.0);
      int checked = 0;
      for (const auto& [leaf, axis] : faces) {
        const BoundingBox box = t.leaf_box(leaf);
        if (box.max[axis] >= t.domain().max[axis]) continue;
        Vec3 x = box.min + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(box.max - box.min);
        x[axis] = box.max[axis];
        const double side = box.max.x() - box.min.x();
        double jump[2][3];
        for (int j = 0; j < 2; ++j) {
          Vec3 e = Vec3::Zero();
          e[axis] = (j == 0 ? 1e-3 : 1e-5) * side;
          Vec3 g0, g1;
          Mat3 h0, h1;
          const double f0 = basis->evaluate(c.data(), x - e, &g0, &h0);
          const double f1 = basis->evaluate(c.data(), x + e, &g1, &h1);
          jump[j][0] = std::abs(f1 - f0);
          jump[j][1] = (g1 - g0).norm() * side;
          jump[j][2] = max_abs(h1 - h0) * side * side;
        }
        INFO("leaf " << leaf << " axis " << axis << " x = " << x.transpose());
        for (int d = 0; d < 3; ++d) {
          INFO("derivative " << d << ": jump " << jump[0][d] << " at h = 1e-3, " << jump[1][d] << " at h = 1e-5");
          CHECK(jump[1][d] <= 0.03 * jump[0][d] + 1e-10);
        }
        ++checked;
      }
      CHECK(checked > 100);
    }
  }
}

TEST_CASE("linear functions are reproduced exactly on the uniform grid away from the boundary", "[tspline][reproduction]") {
  // c_i = Greville abscissae -> f = linear, where all 4^3 blending functions of a cell exist: lattice
  // coordinates in [1, R - 1] (the boundary cells lack the B-splines centred outside the domain).
  const TSplineBasis& basis = *test::uniform_basis();
  const Octree& t = basis.octree();
  const Vec3 a(0.3, -1.7, 0.9);
  const double b = 0.25;
  const std::vector<double> c = quasi_interpolate(basis, [&](const Vec3& x) { return a.dot(x) + b; });
  BoundingBox inner;
  inner.min = t.domain().min + Vec3::Constant(t.unit());
  inner.max = t.domain().max - Vec3::Constant(t.unit());
  for (const Vec3& x : test::random_points(inner, 5000, 20)) {
    Vec3 g;
    Mat3 h;
    CHECK(basis.evaluate(c.data(), x, &g, &h) == Approx(a.dot(x) + b).margin(1e-13));
    CHECK((g - a).norm() <= 1e-12);
    CHECK(max_abs(h) <= 1e-10);
  }
}

namespace {
/// A leaf whose neighbourhood of 3 same-size cells on every side lies in the domain and consists of
/// leaves of its own level: every blending function reaching it is then a uniform B-spline.
bool regular_leaf(const Octree& t, int leaf) {
  const Octree::Cell& c = t.leaf(leaf);
  const int s = t.cell_size(c.level);
  for (int dz = -3; dz <= 3; ++dz)
    for (int dy = -3; dy <= 3; ++dy)
      for (int dx = -3; dx <= 3; ++dx) {
        const Int3 p{c.origin[0] + dx * s, c.origin[1] + dy * s, c.origin[2] + dz * s};
        for (int a = 0; a < 3; ++a)
          if (p[a] < 0 || p[a] >= t.resolution()) return false;
        if (t.leaf(t.leaf_at(p)).level != c.level) return false;
      }
  return true;
}
}  // namespace

TEST_CASE("linear reproduction on the adaptive T-mesh: exact in regular regions, bounded near T-junctions",
          "[tspline][reproduction]") {
  // A T-mesh with a large regular region: points filling the cube [-1,1]^3 (level 4 throughout it),
  // coarser cells in the margin, T-junctions on the transition.
  std::mt19937_64 rng(40);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> cube(30000);
  for (Vec3& p : cube) p = Vec3(u(rng), u(rng), u(rng));
  for (const char* balance : {"face", "edge", "vertex"}) {
    SECTION(balance) {
      TMeshOptions o;
      o.max_depth = 4;
      o.points_per_cell = 4;
      o.balance = balance;
      const TSplineBasis basis(build_octree(cube, o));
      const Octree& t = basis.octree();
      REQUIRE(!test::t_junction_faces(t).empty());
      const Vec3 a(0.3, -1.7, 0.9);
      const std::vector<double> c = quasi_interpolate(basis, [&](const Vec3& x) { return a.dot(x); });
      double worst_regular = 0, worst_other = 0, worst_interior = 0;
      int regular = 0;
      for (const Vec3& x : test::random_points(basis.domain(), 20000, 21)) {
        const int leaf = t.locate(x);
        Vec3 g;
        const double err = std::abs(basis.evaluate(c.data(), x, &g) - a.dot(x)) / (a.norm() * t.leaf_side(leaf));
        if (regular_leaf(t, leaf)) {
          ++regular;
          worst_regular = std::max(worst_regular, err);
        } else {
          worst_other = std::max(worst_other, err);
          if ((x.array().abs() < 1.0).all()) worst_interior = std::max(worst_interior, err);
        }
      }
      WARN(balance << " balance: linear reproduction error / (|grad| x leaf side): regular leaves "
                   << worst_regular << " (" << regular << " points); elsewhere " << worst_other
                   << ", of which inside [-1,1]^3 (no domain-boundary cells) " << worst_interior);
      CHECK(regular > 1000);
      CHECK(worst_regular <= 1e-13);
      // Near T-junctions and the domain boundary the rational form is not exact: bounded by a fraction
      // of the local cell size times the slope.
      CHECK(worst_other <= 0.5);
    }
  }
}

TEST_CASE("quasi-interpolated sphere distance converges like h^2 on the uniform grid", "[tspline][reproduction]") {
  const double r = 0.7;
  const Vec3 centre(0.1, -0.05, 0.02);
  const auto samples = test::sphere_points(3000, r, centre, 22);
  double previous = 0;
  for (int depth = 3; depth <= 5; ++depth) {
    const TSpline f = quasi_interpolant(std::make_shared<TSplineBasis>(uniform_octree(depth, 0.25)),
                                        [&](const Vec3& x) { return (x - centre).norm() - r; });
    double worst = 0;
    for (const Vec3& p : samples) worst = std::max(worst, std::abs(f.value(p)));
    WARN("uniform grid depth " << depth << ": max |f| on the sphere " << worst << " (cell size "
                               << f.tmesh().unit() << ")");
    if (depth > 3) CHECK(worst <= 0.35 * previous);  // O(h^2): a factor 4 per level
    previous = worst;
  }
}

TEST_CASE("quasi-interpolated sphere distance has its zero set near the sphere", "[tspline][reproduction]") {
  const double r = 0.7;
  const Vec3 centre(0.1, -0.05, 0.02);
  const auto samples = test::sphere_points(3000, r, centre, 22);
  auto bases = test::all_bases();
  TMeshOptions o;  // and the T-mesh made from the sphere's own points, as the pipeline does
  o.points_per_cell = 16;
  bases.push_back({"adaptive from the sphere's points", std::make_shared<TSplineBasis>(build_octree(samples, o))});
  for (const auto& [name, basis] : bases) {
    SECTION(name) {
      const TSpline f = quasi_interpolant(basis, [&](const Vec3& x) { return (x - centre).norm() - r; });
      double worst = 0, worst_normal = 1;
      for (const Vec3& p : samples) {
        const double h = basis->octree().leaf_side(basis->octree().locate(p));
        Vec3 g;
        const double v = f.evaluate(p, &g);
        worst = std::max(worst, std::abs(v) / h);
        worst_normal = std::min(worst_normal, g.normalized().dot((p - centre).normalized()));
      }
      WARN(name << ": max |f| on the sphere = " << worst << " x local cell size; min cos(normal error) "
                << worst_normal);
      // The tested meshes put the sphere in cells up to 0.31 wide (h / r up to 0.45), where the
      // quasi-interpolant's O(h^2 / r) error is a sizeable fraction of h.
      CHECK(worst <= 0.2);
      CHECK(worst_normal > 0.8);
    }
  }
}

TEST_CASE("points outside the domain are clamped onto it", "[tspline][eval]") {
  const TSplineBasis& basis = *test::adaptive_basis();
  const std::vector<double> c = test::random_coefficients(basis, 23);
  const BoundingBox d = basis.domain();
  const Vec3 inside(0.3, d.max.y(), d.min.z());
  CHECK(basis.evaluate(c.data(), Vec3(0.3, d.max.y() + 5, d.min.z() - 1)) == basis.evaluate(c.data(), inside));
  CHECK_THROWS_WITH(basis.evaluate(c.data(), Vec3(0.3, std::nan(""), 0)), Catch::Contains("NaN"));
}

TEST_CASE("T-spline rejects coefficient vectors of the wrong size or with NaN", "[tspline][eval]") {
  auto basis = test::adaptive_basis();
  CHECK_THROWS_WITH(TSpline(basis, std::vector<double>(3, 0.0)), Catch::Contains("3 coefficients"));
  std::vector<double> c(basis->size(), 0.0);
  c[5] = std::nan("");
  CHECK_THROWS_WITH(TSpline(basis, c), Catch::Contains("coefficient 5"));
}

TEST_CASE("evaluation is thread-safe", "[tspline][eval]") {
  // The evolution evaluates from OpenMP threads: no shared mutable state in a basis or a T-spline.
  const auto basis = test::adaptive_basis();
  const TSpline f(basis, test::random_coefficients(*basis, 24));
  const auto points = test::random_points(f.domain(), 20000, 25);
  std::vector<double> serial(points.size()), parallel(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) serial[k] = f.value(points[k]);
  auto work = [&](std::size_t begin) {
    ActiveBasis active;
    for (std::size_t k = begin; k < points.size(); k += 2) {
      Vec3 g;
      parallel[k] = f.evaluate(points[k], &g);
      basis->active(points[k], active);
    }
  };
  std::thread a(work, 0), b(work, 1);
  a.join();
  b.join();
  CHECK(serial == parallel);
}
