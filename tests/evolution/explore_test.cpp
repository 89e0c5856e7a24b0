// Temporary exploration (not a property test): prints histories.
#include <catch2/catch.hpp>
#include <iostream>

#include "tests/evolution/fixtures.hpp"
#include "algorithms/evolution/level_set_io.hpp"
#include "framework/config/yaml_options.hpp"
#include "tests/evolution/png_writer.hpp"

using namespace dtsl;

TEST_CASE("explore", "[.explore]") {
  const char* which = std::getenv("EXPLORE");
  std::string w = which ? which : "sphere";
  std::vector<Vec3> pts = w == "torus" ? test::torus_data() : w == "two" ? test::two_spheres_data() : test::sphere_data();
  if (w == "two15")
    pts = test::dataset_points("{name: two, shape: {type: two_spheres, gap: 2.0}, sampler: {type: area, count: 2000}}");
  if (w == "plane") { pts.clear(); for (int i = 0; i < 30; ++i) for (int j = 0; j < 30; ++j) pts.emplace_back(-0.9 + 1.8 * i / 29.0, -0.9 + 1.8 * j / 29.0, 0.0); }
  if (w == "line") { pts.clear(); for (int i = 0; i < 400; ++i) pts.emplace_back(-1.0 + 2.0 * i / 399.0, 0.0, 0.0); }
  if (w == "fandisk")
    pts = test::dataset_points("{name: f, shape: {type: cgal_model, model: fandisk}, sampler: vertices, corruptions: [{type: plane_cut, normal: [0,0,1], offset: 0.75}]}");
  if (w == "bunny")
    pts = test::dataset_points("{name: b, shape: {type: cgal_model, model: bunny00}, sampler: vertices, corruptions: [{type: subsample, count: 6000}]}");
  std::cout << pts.size() << " points\n";
  {
    std::vector<double> nn;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      double best = 1e9;
      for (std::size_t j = 0; j < pts.size(); ++j) if (j != i) best = std::min(best, (pts[i] - pts[j]).norm());
      nn.push_back(best);
    }
    std::sort(nn.begin(), nn.end());
    std::cout << "nn spacing median " << nn[nn.size() / 2] << " p90 " << nn[nn.size() * 9 / 10] << " max " << nn.back() << "\n";
  }
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
              << " band=" << h.band_points << " n=" << h.unknowns << " g=" << h.guarded << " vres=" << h.velocity_residual << " |v|=" << h.mean_speed << "/" << h.max_speed
              << " dist=" << h.mean_distance << "/" << h.max_distance << " sd=" << h.mean_surface_distance << " grad=[" << h.min_gradient << ","
              << h.max_gradient << "]" << (h.solve ? " solve=" + std::to_string(h.solve->seconds) + " it=" + std::to_string(h.solve->iterations) + " " + h.solve->details.dump() : "") << "\n";
  std::cout << r.summary.dump(1) << "\n";
  // Three slices through the origin (x = 0, y = 0, z = 0), side by side: f < 0 shaded, the zero set
  // black, data within 0.03 of the slice red.
  {
    const int S = std::getenv("S") ? std::atoi(std::getenv("S")) : 300;
    std::vector<unsigned char> img(3 * S * 3 * S, 255);
    for (int a = 0; a < 3; ++a) {
      const int u = (a + 1) % 3, w2 = (a + 2) % 3;
      std::vector<double> val(S * S);
      for (int j = 0; j < S; ++j)
        for (int i = 0; i < S; ++i) {
          Vec3 x = Vec3::Zero();
          x[u] = -1.25 + 2.5 * (i + 0.5) / S;
          x[w2] = 1.25 - 2.5 * (j + 0.5) / S;
          val[j * S + i] = r.level_set.evaluate(x);
        }
      for (int j = 0; j < S; ++j)
        for (int i = 0; i < S; ++i) {
          unsigned char* px = &img[3 * (j * 3 * S + a * S + i)];
          const double v = val[j * S + i];
          const bool edge = (i + 1 < S && (val[j * S + i + 1] < 0) != (v < 0)) || (j + 1 < S && (val[(j + 1) * S + i] < 0) != (v < 0));
          if (edge) { px[0] = px[1] = px[2] = 0; }
          else if (v < 0) { px[0] = 170; px[1] = 190; px[2] = 255; }
          else { const int g = 255 - std::min(60, int(std::abs(v) * 100)); px[0] = px[1] = px[2] = g; }
        }
      for (const Vec3& p : pts) {
        if (std::abs(p[a]) > 0.03) continue;
        const int i = int((p[u] + 1.25) / 2.5 * S), j = int((1.25 - p[w2]) / 2.5 * S);
        if (i < 0 || j < 0 || i >= S || j >= S) continue;
        unsigned char* px = &img[3 * (j * 3 * S + a * S + i)];
        px[0] = 230; px[1] = 0; px[2] = 0;
      }
    }
    test::write_png(std::getenv("PNG") ? std::getenv("PNG") : "/tmp/evo_scratch/slice.png", 3 * S, S, img);
  }
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
TEST_CASE("explore cube", "[.explore2]") {
  std::vector<Vec3> points;
  for (int a = 0; a < 3; ++a)
    for (int side = -1; side <= 1; side += 2)
      for (int i = 0; i <= 20; ++i)
        for (int j = 0; j <= 20; ++j) {
          Vec3 p;
          p[a] = side;
          p[(a + 1) % 3] = -1.0 + 0.1 * i;
          p[(a + 2) % 3] = -1.0 + 0.1 * j;
          points.push_back(p);
        }
  EvolutionOptions o = test::test_options("distance", "eigen_cg");
  auto basis = std::make_shared<TSplineBasis>(build_octree(points, o.tmesh));
  const TSpline f = initial_level_set(basis, points, 1.1, 0.1);
  double hi = -1e9;
  for (const Vec3& p : points) hi = std::max(hi, f.evaluate(p));
  std::cout << "max f(p) " << hi << " finest level " << basis->octree().finest_leaf_level() << "\n";
  for (const Vec3& x : {Vec3(1.25, 0, 0), Vec3(1.25, 1.25, 0), Vec3(1.25, 1.25, 1.25), Vec3(1.2, 1.2, 1.2), Vec3(1.1, 1.1, 1.1), Vec3(1.0,1.0,1.0)})
    std::cout << x.transpose() << " f " << f.evaluate(x) << "\n";
  const auto r = marching_cubes(f, points, [] { MarchingCubesOptions m; m.step = 0.05; m.region = "domain"; m.drop_dataless_components = false; return m; }());
  std::cout << r.summary.details.dump() << " open " << r.summary.open_boundaries << "\n";
  const MeshStats s = mesh_stats(r.mesh);
  std::cout << "boundary edges " << s.boundary_edges << " nonmanifold " << s.nonmanifold_edges << " " << s.nonmanifold_vertices << " comps " << s.components << "\n";
}
