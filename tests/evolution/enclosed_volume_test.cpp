// The enclosure check (enclosed_volume.hpp): the carving of a closed surface encloses every data point; a
// sphere cut open by a plane lets the ball pass both sides of the data, the check says so, and the level
// set then starts from the enclosing sphere and ends as one closed surface.
#include <catch2/catch.hpp>

#include <algorithm>

#include "algorithms/evolution/data_carving.hpp"
#include "algorithms/evolution/data_distance.hpp"
#include "algorithms/evolution/data_wrap.hpp"
#include "algorithms/evolution/enclosed_volume.hpp"
#include "algorithms/evolution/support.hpp"
#include "framework/core/error.hpp"
#include "tests/evolution/fixtures.hpp"

using namespace dtsl;
using namespace dtsl::test;

namespace {
// The union of the carving and the wrap, as `evolution_initial: carve` builds it.
EnclosureCheck carve_enclosure(const std::vector<Vec3>& points) {
  const DataCarving carving(points, 2.5);
  const DataWrap wrap(points, 2.5, kWrapOffsetSpacings);
  const std::vector<double> spacing = DataDistance(points).local_spacing(kSpacingNeighbours);
  return check_enclosure(points, spacing, carving.summary().spacing,
                         [&](const Vec3& x) { return std::min(carving(x), wrap(x)); });
}

// A sphere cut open by a plane: a bowl, an open sheet the carving ball passes on both sides.
const std::vector<Vec3>& cut_sphere_data() {
  static const std::vector<Vec3> p = dataset_points(
      "{name: bowl, shape: sphere, sampler: {type: area, count: 3000}, "
      "corruptions: [{type: plane_cut, normal: [1, 0, 1], offset: 0.4}]}");
  return p;
}
}  // namespace

TEST_CASE("the carving of closed surfaces encloses their data", "[carve][enclosure]") {
  for (const std::vector<Vec3>* points : {&torus_data(), &two_spheres_data()}) {
    const EnclosureCheck check = carve_enclosure(*points);
    INFO(check.unenclosed << " of " << check.tested);
    CHECK(check.tested > 1000);
    CHECK(check.fraction() < 0.2 * kMaxUnenclosedFraction);
  }
}

TEST_CASE("a sphere cut open by a plane leaves its data unenclosed", "[carve][enclosure]") {
  const EnclosureCheck check = carve_enclosure(cut_sphere_data());
  INFO(check.unenclosed << " of " << check.tested);
  CHECK(check.fraction() > kMaxUnenclosedFraction);
}

TEST_CASE("the enclosure check tests at most the number asked and counts what it tests", "[enclosure]") {
  const std::vector<Vec3>& points = torus_data();
  const std::vector<double> spacing(points.size(), 0.05);
  const EnclosureCheck everywhere_inside = check_enclosure(points, spacing, 0.05, [](const Vec3&) { return -1.0; });
  CHECK(everywhere_inside.tested <= 2000);
  CHECK(everywhere_inside.tested >= 1000);  // evenly strided over the 2500 points
  CHECK(everywhere_inside.unenclosed == 0);
  const EnclosureCheck nowhere_inside = check_enclosure(points, spacing, 0.05, [](const Vec3&) { return 1.0; }, 100);
  CHECK(nowhere_inside.tested <= 100);
  CHECK(nowhere_inside.unenclosed == nowhere_inside.tested);
  CHECK_THROWS_AS(check_enclosure(points, std::vector<double>(3, 0.05), 0.05, [](const Vec3&) { return 1.0; }),
                  AlgorithmError);
}

TEST_CASE("a cut-open sphere starts from the enclosing sphere and ends as one closed surface", "[carve][enclosure]") {
  const std::vector<Vec3>& points = cut_sphere_data();
  EvolutionOptions o = test_options("distance_balloon", "eigen_cg", 5);
  o.initial = "carve";
  o.wrap_alpha = 2.5;
  o.final_refinement = false;
  o.fine.levels = 1;
  const LevelSetResult r = compute_level_set(points, o);
  INFO(r.summary["initial"].dump());
  REQUIRE(r.summary.contains("initial"));
  CHECK(r.summary["initial"]["unenclosed_fraction"].get<double>() > kMaxUnenclosedFraction);
  CHECK(r.summary["initial"]["fallback"] == "sphere");
  // The parts the start ran before falling back are timed; the refinement toward the data did not run.
  CHECK(r.summary["initial"]["timings"]["carving_and_wraps"].get<double>() >= 0.0);
  CHECK(r.summary["initial"]["timings"]["enclosure"].get<double>() >= 0.0);
  CHECK(!r.summary["initial"]["timings"].contains("refinement_and_fit"));
  const MeshStats s = mesh_stats(zero_set_mesh(r.level_set, points));
  CHECK(s.components == 1);
  CHECK(s.genus == 0.0);
  CHECK(s.watertight);
}
