// The final refinement's topology guard (refinement_guard.hpp): the fit is kept whole when it adds no
// components or handles, scaled back to the first alpha that adds none, or dropped (alpha = 0, the
// transferred level set); a level set that cannot be meshed is no reference. The topology function is
// a stand-in here (the choice is the unit under test); the pipeline test checks the real thing.
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <memory>

#include "algorithms/method/refinement_guard.hpp"
#include "algorithms/tspline/octree.hpp"
#include "framework/core/error.hpp"

using namespace dtsl;

namespace {

struct Splines {
  TSpline evolved, fitted;
  std::vector<double> transferred;
};

Splines splines() {
  std::vector<Vec3> points;
  for (int k = 0; k < 400; ++k) {
    const double t = 0.1 * k, z = -0.9 + 1.8 * k / 399.0, r = std::sqrt(1 - z * z) * 0.7;
    points.emplace_back(r * std::cos(t), r * std::sin(t), 0.7 * z);
  }
  auto basis = std::make_shared<TSplineBasis>(build_octree(points, TMeshOptions{}));
  std::vector<double> c0(basis->size()), c1(basis->size());
  for (std::size_t i = 0; i < c0.size(); ++i) {
    c0[i] = 0.5 - 0.001 * double(i % 7);
    c1[i] = -0.25 + 0.002 * double(i % 5);
  }
  return {TSpline(basis, c0), TSpline(basis, c1), c0};
}

/// Topology by alpha (-1: the evolved reference), recording the calls and the splines asked about.
struct Script {
  std::map<double, std::optional<ZeroSetTopology>> by_alpha;
  std::vector<double> asked;
  std::vector<std::vector<double>> coefficients;
  TopologyOf function() {
    return [this](const TSpline& candidate, double alpha) {
      asked.push_back(alpha);
      coefficients.push_back(candidate.coefficients());
      return by_alpha.at(alpha);
    };
  }
};

}  // namespace

TEST_CASE("no_more_complex: components never more; genus never larger where both meshes are closed", "[guard]") {
  CHECK(no_more_complex({1, 0.0}, {1, 0.0}));
  CHECK(no_more_complex({1, 0.0}, {1, 1.0}));  // a fit that closes a spurious handle is welcome
  CHECK_FALSE(no_more_complex({2, 0.0}, {1, 0.0}));
  CHECK_FALSE(no_more_complex({1, 2.0}, {1, 1.0}));
  CHECK_FALSE(no_more_complex({1, NAN}, {1, 0.0}));  // a closed zero set may not open
  CHECK(no_more_complex({1, 0.0}, {1, NAN}));         // an open one: components only
  CHECK(no_more_complex({1, NAN}, {2, NAN}));
  CHECK_FALSE(no_more_complex({3, NAN}, {2, NAN}));
}

TEST_CASE("refinement guard: the whole fit when it keeps the topology, one check each", "[guard]") {
  const Splines s = splines();
  Script script;
  script.by_alpha = {{-1.0, ZeroSetTopology{1, 1.0}}, {1.0, ZeroSetTopology{1, 0.0}}};
  const GuardedRefinement g = guard_refinement_topology(s.evolved, s.fitted, s.transferred, script.function());
  CHECK(g.alpha == 1.0);
  CHECK(g.level_set.coefficients() == s.fitted.coefficients());
  CHECK(script.asked == std::vector<double>{-1.0, 1.0});
  CHECK(g.summary["kept_alpha"] == 1.0);
}

TEST_CASE("refinement guard: a fit that severs a part is scaled back to the first alpha that does not", "[guard]") {
  const Splines s = splines();
  Script script;
  script.by_alpha = {{-1.0, ZeroSetTopology{1, 0.0}},
                     {1.0, ZeroSetTopology{15, 1.0}},
                     {0.5, ZeroSetTopology{5, 0.0}},
                     {0.25, ZeroSetTopology{1, 0.0}}};
  const GuardedRefinement g = guard_refinement_topology(s.evolved, s.fitted, s.transferred, script.function());
  CHECK(g.alpha == 0.25);
  const std::vector<double>& c = g.level_set.coefficients();
  REQUIRE(c.size() == s.transferred.size());
  for (std::size_t i = 0; i < c.size(); ++i)
    CHECK(c[i] == Approx(0.75 * s.transferred[i] + 0.25 * s.fitted.coefficients()[i]).margin(1e-15));
  CHECK(g.level_set.shared_basis() == s.fitted.shared_basis());
  CHECK(g.summary["tried"].size() == 3);
  // What was meshed: the evolved level set, then f_1 = the fit, f_1/2, f_1/4.
  REQUIRE(script.coefficients.size() == 4);
  CHECK(script.coefficients[0] == s.evolved.coefficients());
  CHECK(script.coefficients[1] == s.fitted.coefficients());
  for (std::size_t i = 0; i < c.size(); i += 17) {
    CHECK(script.coefficients[2][i] == Approx(0.5 * (s.transferred[i] + s.fitted.coefficients()[i])).margin(1e-15));
    CHECK(script.coefficients[3][i] == Approx(c[i]).margin(1e-15));
  }
}

TEST_CASE("refinement guard: every scaled fit worse, or unmeshable, gives the transferred level set", "[guard]") {
  const Splines s = splines();
  Script script;
  script.by_alpha = {{-1.0, ZeroSetTopology{1, 0.0}},
                     {1.0, ZeroSetTopology{2, 0.0}},
                     {0.5, std::nullopt},
                     {0.25, ZeroSetTopology{1, 1.0}}};
  const GuardedRefinement g = guard_refinement_topology(s.evolved, s.fitted, s.transferred, script.function());
  CHECK(g.alpha == 0.0);
  CHECK(g.level_set.coefficients() == s.transferred);
  CHECK(g.summary["tried"][1]["topology"] == "not meshed");
}

TEST_CASE("refinement guard: no reference when the evolved level set cannot be meshed; bad input named", "[guard]") {
  const Splines s = splines();
  Script script;
  script.by_alpha = {{-1.0, std::nullopt}};
  const GuardedRefinement g = guard_refinement_topology(s.evolved, s.fitted, s.transferred, script.function());
  CHECK(g.alpha == 1.0);
  CHECK(script.asked == std::vector<double>{-1.0});
  CHECK_THAT(g.summary["reason"].get<std::string>(), Catch::Contains("no reference"));

  std::vector<double> short_transfer(s.transferred.begin(), s.transferred.end() - 1);
  CHECK_THROWS_WITH(guard_refinement_topology(s.evolved, s.fitted, short_transfer, script.function()),
                    Catch::Contains("transferred coefficients"));
  CHECK_THROWS_WITH(guard_refinement_topology(s.evolved, s.fitted, s.transferred, script.function(), {0.5}),
                    Catch::Contains("first alpha must be 1"));
  CHECK_THROWS_WITH(guard_refinement_topology(s.evolved, s.fitted, s.transferred, script.function(), {1.0, 0.5, 0.7}),
                    Catch::Contains("alphas must decrease"));
}
