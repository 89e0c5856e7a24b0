#include <catch2/catch.hpp>
#include <cstdlib>
#include <iostream>

#include "algorithms/sharpen/bilateral_evolution.hpp"
#include "framework/metrics/metrics.hpp"
#include "framework/core/timer.hpp"
#include "tests/sharpen/block_fixture.hpp"

using namespace dtsl;

TEST_CASE("explore block", "[.explore]") {
  Stopwatch t;
  const TriangleMesh truth = sharpen_test::block_truth();
  const auto pts = sharpen_test::block_points(truth, 30000, 1);
  const double delta = 0.03;
  const TriangleMesh start = sharpen_test::rounded_block_mesh(2 * delta, delta);
  auto st = mesh_stats(start);
  std::cout << "setup " << t.seconds() << " s, start V " << start.vertices.size() << " F " << start.faces.size()
            << " watertight " << st.watertight << " genus " << st.genus << " minangle " << st.min_angle_deg << "\n";
  sharpen::BilateralEvolutionOptions o;
  o.delta = delta;
  if (getenv("DEG")) o.degenerate.max_passes = atoi(getenv("DEG"));
  if (getenv("W")) o.bilateral_weight = atof(getenv("W"));
  if (getenv("IT")) o.max_iterations = atoi(getenv("IT"));
  if (getenv("SF")) o.sigma_factor = atof(getenv("SF"));
  if (getenv("ER")) o.sharp.error_ratio = atof(getenv("ER"));
  t.restart();
  auto r = sharpen::bilateral_evolution(start, pts, o);
  std::cout << "evolution " << t.seconds() << " s\n" << r.summary.dump(1) << "\n";
  double d0 = 0, d1 = 0;
  for (int v : r.sharp_vertices) d1 += sharpen_test::distance_to_block_edges(r.mesh.vertices[v]);
  std::cout << "mean dist sharp to edges " << d1 / r.sharp_vertices.size() << "\n";
  auto st2 = mesh_stats(r.mesh);
  std::cout << "end watertight " << st2.watertight << " genus " << st2.genus << " minangle " << st2.min_angle_deg << "\n";
  for (int v : r.sharp_vertices) (void)v;
  auto edges = sharpen_test::block_edge_points(0.01);
  std::cout << "edge points to mesh: start " << point_errors(edges, start).e_avr << " end " << point_errors(edges, r.mesh).e_avr << "\n";
  std::cout << "truth e_avr " << point_errors(pts, truth).e_avr << " start " << point_errors(pts, start).e_avr << " end " << point_errors(pts, r.mesh).e_avr << " Vstart " << start.vertices.size() << "\n";
  if (r.mesh.faces.size() == start.faces.size()) {
    int fl = 0, flsmall = 0;
    for (size_t f = 0; f < start.faces.size(); ++f) {
      double d = face_normal(r.mesh, f).dot(face_normal(start, f));
      if (d <= 0) { ++fl; if (face_area(start, f) < 1e-6) ++flsmall; }
    }
    std::cout << "same-index flips " << fl << " (small start area " << flsmall << ")\n";
  }
  {
    MeshDistance sd(start);
    int fl = 0;
    for (size_t f = 0; f < r.mesh.faces.size(); ++f) {
      if (face_area(r.mesh, f) < 1e-10) continue;
      const Face& t = r.mesh.faces[f];
      Vec3 c = (r.mesh.vertices[t[0]] + r.mesh.vertices[t[1]] + r.mesh.vertices[t[2]]) / 3.0;
      auto hit = sd.closest(c);
      double d = face_normal(r.mesh, f).dot(face_normal(start, hit.face));
      if (d <= 0) { ++fl; if (fl < 8) std::cout << "  flip f " << f << " area " << face_area(r.mesh, f) << " dot " << d << " dist " << hit.distance << " edgedist " << sharpen_test::distance_to_block_edges(c) << "\n"; }
    }
    std::cout << "closest-face flips " << fl << "\n";
  }
  (void)d0;
}
