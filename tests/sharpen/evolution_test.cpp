// The bilateral evolution as a whole beyond the block: the two solvers give the same evolution, a smooth
// sphere is left alone, bad input and bad options are clear errors.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>

#include "algorithms/sharpen/bilateral_evolution.hpp"
#include "framework/core/error.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/sharpen/block_fixture.hpp"

using namespace dtsl;
using namespace dtsl::sharpen;

namespace {

class Sphere final : public ImplicitFunction {
 public:
  double evaluate(const Vec3& x, Vec3* g, Mat3* hess) const override {
    if (g) *g = x.norm() > 0 ? Vec3(x.normalized()) : Vec3(0, 0, 1);
    if (hess) hess->setZero();
    return x.norm() - 0.8;
  }
  BoundingBox domain() const override {
    BoundingBox b;
    b.extend(Vec3::Constant(-1.01));
    b.extend(Vec3::Constant(1.02));
    return b;
  }
};

/// 15k points on the block (the start mesh of both tests below: the block rounded by 0.08).
std::vector<Vec3> block_data() { return sharpen_test::block_points(sharpen_test::block_truth(), 15000, 11); }

}  // namespace

TEST_CASE("eigen_ldlt and ceres drive the same evolution on the block", "[sharpen][solver]") {
  const auto points = block_data();
  const TriangleMesh start = sharpen_test::rounded_block_mesh(0.08, 0.04);
  BilateralEvolutionOptions o;
  o.delta = 0.04;
  // One step, no removal: the same problem, so the same velocities up to solver round-off.
  o.max_iterations = 1;
  o.degenerate.max_passes = 0;
  o.solver = "eigen_ldlt";
  const auto a = bilateral_evolution(start, points, o);
  o.solver = "ceres";
  const auto b = bilateral_evolution(start, points, o);
  const auto& ha = a.summary["e_avr_per_iteration"];
  const auto& hb = b.summary["e_avr_per_iteration"];
  REQUIRE(ha.size() == 2);
  REQUIRE(hb.size() == 2);
  CHECK(hb[1].get<double>() == Approx(ha[1].get<double>()).epsilon(1e-6));
  CHECK(ha[1].get<double>() < ha[0].get<double>());
  REQUIRE(a.mesh.vertices.size() == b.mesh.vertices.size());
  double worst = 0.0;
  for (std::size_t v = 0; v < a.mesh.vertices.size(); ++v)
    worst = std::max(worst, (a.mesh.vertices[v] - b.mesh.vertices[v]).norm());
  CHECK(worst < 1e-7);
  CHECK(b.summary["solver"] == "ceres");
  // Whole runs: the sharp set and the flip freezing are thresholds, so round-off may change a few
  // decisions; the results still agree closely.
  o.max_iterations = 5;
  o.degenerate = DegenerateRemovalOptions();
  o.solver = "eigen_ldlt";
  const double ea = bilateral_evolution(start, points, o).summary["e_avr_final"].get<double>();
  o.solver = "ceres";
  const double eb = bilateral_evolution(start, points, o).summary["e_avr_final"].get<double>();
  CHECK(eb == Approx(ea).epsilon(0.02));
}

TEST_CASE("StoppingRule: a rise stops at once, slow steps only the patience-th in a row", "[sharpen][stop]") {
  // Feeds a sequence of e_avr values (the best so far updated on every step taken); returns the index of
  // the step that stops and its reason, or (-1, "") if none does.
  const auto run = [](double threshold, int patience, const std::vector<double>& e) {
    StoppingRule rule(threshold, patience);
    double best = 1.0;
    for (std::size_t k = 0; k < e.size(); ++k) {
      const std::string why = rule.judge(e[k], best);
      if (!why.empty()) return std::make_pair(int(k), why);
      best = e[k];
    }
    return std::make_pair(-1, std::string());
  };
  // Gains of 10 %, 0.05 % (slow), 10 %, 0.05 %, 0.05 %: patience 2 goes on after a lone slow step.
  const std::vector<double> pause = {0.9, 0.89955, 0.809595, 0.80919, 0.80879};
  CHECK(run(1e-3, 1, pause) == std::make_pair(1, std::string("slow")));
  CHECK(run(1e-3, 2, pause) == std::make_pair(4, std::string("slow")));  // slow in a row, not in total
  CHECK(run(1e-3, 3, pause) == std::make_pair(-1, std::string()));
  // A rise, or no change, stops whatever the patience, even right after a fast step.
  CHECK(run(1e-3, 3, {0.9, 0.95}) == std::make_pair(1, std::string("rose")));
  CHECK(run(1e-3, 3, {0.9, 0.9}) == std::make_pair(1, std::string("rose")));
  CHECK(run(1e-3, 3, {0.9, std::nan("")}) == std::make_pair(1, std::string("rose")));
  // Threshold 0: every fall counts, so only a rise stops (the paper's rule word for word).
  CHECK(run(0.0, 1, pause) == std::make_pair(-1, std::string()));
  // Patience 1 is the rule before patience existed: stop when e is not below best x (1 - threshold).
  std::mt19937 random(3);
  std::uniform_real_distribution<double> change(-0.01, 0.05), threshold(0.0, 0.02);
  for (int trial = 0; trial < 1000; ++trial) {
    const double t = threshold(random), best = 1.0, e = best * (1.0 - change(random));
    StoppingRule rule(t, 1);
    CHECK(rule.judge(e, best).empty() == (e < best * (1.0 - t)));
  }
}

TEST_CASE("the stopping rule: slow steps are taken until the patience-th in a row, which is not", "[sharpen][stop]") {
  const auto points = block_data();
  const TriangleMesh start = sharpen_test::rounded_block_mesh(0.08, 0.04);
  BilateralEvolutionOptions o;
  o.delta = 0.04;
  o.degenerate.max_passes = 0;
  o.min_relative_decrease = 0.9;  // no step gains 90 %: every step is slow
  for (int patience : {1, 2, 3}) {
    o.patience = patience;
    const auto r = bilateral_evolution(start, points, o);
    const auto& h = r.summary["e_avr_per_iteration"];
    INFO("patience " << patience);
    REQUIRE(h.size() == std::size_t(patience) + 1);  // the initial e_avr, then one per step tried
    CHECK(r.summary["iterations"].get<int>() == patience - 1);
    CHECK(r.summary["stop_reason"] == "e_avr stopped falling");
    CHECK(r.summary["stop_detail"] == "slow");
    for (int k = 1; k <= patience; ++k) CHECK(h[k].get<double>() < h[k - 1].get<double>());  // each still falls
    // The result is the last step taken, not the one that stopped the loop.
    CHECK(r.summary["e_avr_evolved"].get<double>() == h[patience - 1].get<double>());
    CHECK(r.summary["e_avr_final"].get<double>() == Approx(h[patience - 1].get<double>()).epsilon(1e-12));
  }
  // With a threshold no step misses, the cap ends it.
  o.min_relative_decrease = 0.0;
  o.patience = 1;
  o.max_iterations = 2;
  CHECK(bilateral_evolution(start, points, o).summary["iterations"].get<int>() == 2);
}

TEST_CASE("on a smooth sphere almost nothing is sharp and the mesh barely moves", "[sharpen][sphere]") {
  MarchingCubesOptions mc;
  mc.step = 0.05;
  const TriangleMesh start = marching_cubes(Sphere(), {}, mc).mesh;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<Vec3> points;
  for (int k = 0; k < 20000; ++k) {
    const Vec3 d(n(rng), n(rng), n(rng));
    points.push_back(0.8 * d.normalized() + 0.001 * n(rng) * d.normalized());  // a little noise
  }
  BilateralEvolutionOptions o;
  o.delta = 0.05;
  const auto r = bilateral_evolution(start, points, o);
  const std::size_t sharp = r.summary["sharp_vertices"].get<std::size_t>();
  INFO("sharp " << sharp << " of " << start.vertices.size() << "; " << r.summary.dump());
  CHECK(sharp <= start.vertices.size() / 100);
  CHECK(mesh_stats(r.mesh).watertight);
  // Barely moves: against the start surface, within a small fraction of delta.
  const SurfaceMetrics m = compare_surfaces(r.mesh, start, 20000, 0.005, 3);
  std::cout << "sphere: " << sharp << " sharp of " << start.vertices.size() << " vertices, hausdorff to the start "
            << m.hausdorff << ", e_avr " << r.summary["e_avr_initial"] << " -> " << r.summary["e_avr_final"] << "\n";
  CHECK(m.hausdorff < 0.1 * o.delta);
  CHECK(r.summary["e_avr_final"].get<double>() <= r.summary["e_avr_initial"].get<double>() * 1.001);
}

TEST_CASE("bad input to the bilateral evolution is a clear error", "[sharpen][errors]") {
  TriangleMesh tet;
  tet.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tet.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const std::vector<Vec3> pts = {{0.2, 0.2, -0.01}, {0.3, 0.3, 0.3}};
  BilateralEvolutionOptions o;
  CHECK_NOTHROW(bilateral_evolution(tet, pts, o));
  CHECK_THROWS_WITH(bilateral_evolution(tet, {}, o), Catch::Contains("no data points"));
  std::vector<Vec3> nan = pts;
  nan[1].y() = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(bilateral_evolution(tet, nan, o), AlgorithmError);
  CHECK_THROWS_WITH(bilateral_evolution(tet, nan, o), Catch::Contains("data point 1"));
  CHECK_THROWS_WITH(bilateral_evolution(TriangleMesh{}, pts, o), Catch::Contains("no faces"));
  TriangleMesh bad_vertex = tet;
  bad_vertex.vertices[2].x() = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(bilateral_evolution(bad_vertex, pts, o), Catch::Contains("vertex 2"));
  TriangleMesh bad_index = tet;
  bad_index.faces[3][1] = 9;
  CHECK_THROWS_AS(bilateral_evolution(bad_index, pts, o), AlgorithmError);
}

TEST_CASE("options: check() names the broken field, visit() lists every field with a doc", "[sharpen][options]") {
  auto broken = [](auto change) {
    BilateralEvolutionOptions o;
    change(o);
    return o;
  };
  CHECK_NOTHROW(BilateralEvolutionOptions().check());
  CHECK_THROWS_WITH(broken([](auto& o) { o.delta = 0.0; }).check(), Catch::StartsWith("delta"));
  CHECK_THROWS_WITH(broken([](auto& o) { o.time_step = 2.0; }).check(), Catch::StartsWith("time_step"));
  CHECK_THROWS_WITH(broken([](auto& o) { o.bilateral_weight = -1.0; }).check(), Catch::StartsWith("bilateral_weight"));
  CHECK_THROWS_WITH(broken([](auto& o) { o.solver = "cholmod"; }).check(), Catch::StartsWith("solver"));
  CHECK_THROWS_WITH(broken([](auto& o) { o.max_iterations = -1; }).check(), Catch::StartsWith("max_iterations"));
  CHECK_THROWS_WITH(broken([](auto& o) { o.patience = 0; }).check(), Catch::StartsWith("patience"));
  CHECK_THROWS_WITH(broken([](auto& o) { o.sharp.error_ratio = -1.0; }).check(),
                    Catch::StartsWith("sharp_error_ratio"));
  CHECK_THROWS_WITH(broken([](auto& o) { o.sharp.dihedral_angle_deg = 200.0; }).check(),
                    Catch::StartsWith("sharp_dihedral_angle_deg"));
  CHECK_THROWS_WITH(broken([](auto& o) { o.degenerate.min_edge_ratio = 2.0; }).check(),
                    Catch::StartsWith("degenerate_min_edge_ratio"));
  CHECK_THROWS_AS(bilateral_evolution(TriangleMesh{}, {}, broken([](auto& o) { o.delta = -1.0; })), ConfigError);

  struct Lister final : FieldVisitor {
    std::vector<std::string> names;
    bool all_documented = true;
    void note(const char* n, const char* d) {
      names.push_back(n);
      all_documented &= d != nullptr && std::string(d).size() > 5;
    }
    void field(const char* n, bool&, const char* d) override { note(n, d); }
    void field(const char* n, int&, const char* d) override { note(n, d); }
    void field(const char* n, double&, const char* d) override { note(n, d); }
    void field(const char* n, std::string&, const char* d) override { note(n, d); }
    void field(const char* n, std::vector<double>&, const char* d) override { note(n, d); }
  } lister;
  BilateralEvolutionOptions o;
  o.visit(lister);
  CHECK(lister.all_documented);
  CHECK(std::find(lister.names.begin(), lister.names.end(), "sharp_normal_variation_deg") != lister.names.end());
  CHECK(std::find(lister.names.begin(), lister.names.end(), "patience") != lister.names.end());
  // Constants of the method are no options (delta is handed over by the pipeline).
  CHECK(std::find(lister.names.begin(), lister.names.end(), "degenerate_max_passes") == lister.names.end());
  CHECK(std::find(lister.names.begin(), lister.names.end(), "delta") == lister.names.end());
}
