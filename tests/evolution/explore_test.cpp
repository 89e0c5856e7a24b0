// Temporary exploration (not a property test): prints histories.
#include <catch2/catch.hpp>
#include <iostream>

#include "tests/evolution/fixtures.hpp"
#include "algorithms/evolution/level_set_io.hpp"
#include "framework/config/yaml_options.hpp"

using namespace dtsl;

TEST_CASE("explore", "[.explore]") {
  const char* which = std::getenv("EXPLORE");
  std::string w = which ? which : "sphere";
  std::vector<Vec3> pts = w == "torus" ? test::torus_data() : w == "two" ? test::two_spheres_data() : test::sphere_data();
  if (w == "fandisk")
    pts = test::dataset_points("{name: f, shape: {type: cgal_model, model: fandisk}, sampler: vertices, corruptions: [{type: plane_cut, normal: [0,0,1], offset: 0.75}]}");
  if (w == "bunny")
    pts = test::dataset_points("{name: b, shape: {type: cgal_model, model: bunny00}, sampler: vertices, corruptions: [{type: subsample, count: 6000}]}");
  std::cout << pts.size() << " points\n";
  EvolutionOptions o = test::test_options(std::getenv("VEL") ? std::getenv("VEL") : "distance_balloon",
                                          std::getenv("SOL") ? std::getenv("SOL") : "eigen_ldlt",
                                          std::getenv("DEPTH") ? std::atoi(std::getenv("DEPTH")) : 4);
  if (std::getenv("NOREF")) o.final_refinement = false;
  for (const char* kv : {"SET1", "SET2", "SET3", "SET4"})
    if (const char* a = std::getenv(kv)) {
      std::string t = a;
      auto eq = t.find('=');
      apply_assignment(o, t.substr(0, eq), t.substr(eq + 1), "explore");
    }
  const LevelSetResult r = compute_level_set(pts, o);
  for (const auto& h : r.history)
    std::cout << h.iteration << " t=" << h.seconds << " dt=" << h.time_step << " xs=" << h.surface_points
              << " band=" << h.band_points << " n=" << h.unknowns << " |v|=" << h.mean_speed << "/" << h.max_speed
              << " dist=" << h.mean_distance << "/" << h.max_distance << " grad=[" << h.min_gradient << ","
              << h.max_gradient << "]" << (h.solve ? " solve=" + std::to_string(h.solve->seconds) + " it=" + std::to_string(h.solve->iterations) + " " + h.solve->details.dump() : "") << "\n";
  std::cout << r.summary.dump(1) << "\n";
  for (const TSpline* f : {&r.evolved, &r.level_set}) {
    const TriangleMesh m = test::zero_set_mesh(*f, pts);
    const MeshStats s = mesh_stats(m);
    const auto nd = test::newton_distances(*f, pts);
    const auto gr = test::gradient_range_on_zero_set(*f, m);
    std::cout << "genus " << s.genus << " components " << s.components << " watertight " << s.watertight
              << " newton mean " << nd.mean << " max " << nd.max << " failed " << nd.failed << " grad [" << gr.first
              << ", " << gr.second << "]\n";
  }
}
