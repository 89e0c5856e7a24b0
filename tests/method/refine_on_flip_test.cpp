// Paper §3.2's refine-on-flip loop (algorithms/method/refine_on_flip.hpp): a round whose refined level set
// does not mesh at MI's step, or meshes with another topology, is refused before it is displaced, and
// the displacement of the unrefined MI is what comes out; a displaced round is kept only with fewer flips and
// the data no farther from it.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "algorithms/evolution/evolution.hpp"
#include "algorithms/evolution/initial_level_set.hpp"
#include "algorithms/method/refine_on_flip.hpp"
#include "algorithms/polygonize/marching_cubes.hpp"
#include "framework/core/error.hpp"

using namespace dtsl;

namespace {

// Points on a sphere of radius 0.5 with radial noise of +-0.1: rougher than MI's edges, so displacing the
// smooth initial sphere onto them flips triangles.
std::vector<Vec3> rough_sphere(int n) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> noise(-0.1, 0.1);
  std::vector<Vec3> out;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z);
    out.push_back((0.5 + noise(rng)) * Vec3(r * std::cos(golden * i), r * std::sin(golden * i), z));
  }
  return out;
}

struct Setup {
  std::vector<Vec3> points = rough_sphere(3000);
  EvolutionOptions evolution;
  MeshedLevelSet base;
  DisplacementOptions displace;
  Setup()
      : base{initial_level_set(std::make_shared<TSplineBasis>(build_octree(points, evolution.tmesh)), points, 1.1, 0.1),
             PolygonizeResult{}, 0.06, 0, ""} {
    MarchingCubesOptions cubes;
    cubes.step = base.step;
    base.mi = marching_cubes(base.f, points, cubes);
    displace.filter = "gaussian";
  }
  FlipRefinement how() const {
    FlipRefinement h;
    h.rounds = 2;
    h.refine = evolution.refinement;
    h.solver = evolution.solver;
    h.check = [](TriangleMesh&) {};
    return h;
  }
};

}  // namespace

TEST_CASE("refine-on-flip refuses a refined level set that does not mesh at MI's step, or changes the topology",
          "[method][flips]") {
  Setup s;
  const DisplacementResult unrefined = displace_mesh(s.base.f, s.base.mi.mesh, s.points, s.displace);
  REQUIRE(unrefined.needs_refinement);  // the premise: this input flips triangles
  const std::vector<double> coefficients = s.base.f.coefficients();

  SECTION("does not mesh at MI's step: one attempt, at that step, then refused") {
    FlipRefinement how = s.how();
    std::vector<double> steps;
    how.triangulate = [&](MeshedLevelSet& m) {
      steps.push_back(m.step);
      throw AlgorithmError("marching triangulation: the front cannot close at this step");
    };
    MeshedLevelSet current = s.base;
    const DisplacementResult r = displace_refining_on_flips(current, s.points, s.points, s.displace, how);
    REQUIRE(steps.size() == 1);
    CHECK(steps[0] == s.base.step);
    CHECK(r.summary["flips_per_round"].back() == "does not mesh at MI's step: refused");
    CHECK(current.f.coefficients() == coefficients);
    CHECK(r.mesh.vertices == unrefined.mesh.vertices);
  }
  SECTION("another topology: refused without displacing the refined mesh") {
    FlipRefinement how = s.how();
    how.triangulate = [&](MeshedLevelSet& m) {  // MI and a second, disjoint copy of it: two components
      m.mi = s.base.mi;
      TriangleMesh& mesh = m.mi.mesh;
      const int n = int(mesh.vertices.size()), faces = int(mesh.faces.size());
      for (int v = 0; v < n; ++v) mesh.vertices.push_back(mesh.vertices[v] + Vec3(3.0, 0.0, 0.0));
      for (int t = 0; t < faces; ++t) {
        auto face = mesh.faces[t];
        for (auto& v : face) v += n;
        mesh.faces.push_back(face);
      }
    };
    MeshedLevelSet current = s.base;
    const DisplacementResult r = displace_refining_on_flips(current, s.points, s.points, s.displace, how);
    CHECK(r.summary["flips_per_round"].back() == "topology changed: refused");
    const nlohmann::json& rounds = r.summary["refinement_round_seconds"];
    REQUIRE(rounds.size() == 1);
    CHECK(!rounds[0].contains("displace"));
    CHECK(current.f.coefficients() == coefficients);
    CHECK(r.mesh.vertices == unrefined.mesh.vertices);
  }
}

TEST_CASE("refine-on-flip keeps a round only with fewer flips and the data no farther (e_avr)", "[method][flips]") {
  const auto result = [](int flips, double e_avr) {
    DisplacementResult r;
    r.flipped_faces.assign(std::size_t(flips), 0);
    r.summary["errors_after"] = {{"e_avr", e_avr}, {"e_max", 10 * e_avr}};
    return r;
  };
  const DisplacementResult kept = result(20, 1e-3);
  CHECK(mean_data_distance(kept) == 1e-3);
  CHECK(round_refusal(kept, result(5, 0.9e-3)).empty());
  CHECK(round_refusal(kept, result(19, 1e-3)).empty());
  CHECK(round_refusal(kept, result(20, 0.5e-3)) == "20 flips, not fewer: refused");
  CHECK(round_refusal(kept, result(30, 0.5e-3)) == "30 flips, not fewer: refused");
  CHECK(round_refusal(kept, result(5, 1.1e-3)) == "5 flips but e_avr rose: refused");
}
