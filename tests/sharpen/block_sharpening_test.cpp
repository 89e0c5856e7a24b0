// Phase 3 on the CAD-like block: starting from a mesh that fits the data except along
// the rounded sharp edges (what a displaced mesh looks like), the bilateral evolution must halve e_avr,
// bring the mesh onto the true edge lines, move only vertices near those edges, flip no triangle, and
// keep the mesh closed, manifold and of genus 1.
#include <catch2/catch.hpp>
#include <iostream>

#include "algorithms/sharpen/bilateral_evolution.hpp"
#include "framework/core/sampling.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/sharpen/block_fixture.hpp"

using namespace dtsl;
using namespace dtsl::sharpen_test;

namespace {

constexpr double kDelta = 0.03;

struct BlockRun {
  TriangleMesh truth, start;
  std::vector<Vec3> points;
  sharpen::BilateralEvolutionResult result;
};

const BlockRun& block_run() {
  static const BlockRun run = [] {
    BlockRun r;
    r.truth = block_truth();
    r.points = block_points(r.truth, 30000, 7);
    r.start = rounded_block_mesh(2 * kDelta, kDelta);
    sharpen::BilateralEvolutionOptions o;
    o.delta = kDelta;
    r.result = sharpen::bilateral_evolution(r.start, r.points, o);
    std::cout << "block sharpening summary: " << r.result.summary.dump() << "\n";
    return r;
  }();
  return run;
}

}  // namespace

TEST_CASE("block: the bilateral evolution at least halves e_avr", "[sharpen][block]") {
  const BlockRun& r = block_run();
  const double before = point_errors(r.points, r.start).e_avr;
  const double after = point_errors(r.points, r.result.mesh).e_avr;
  INFO("e_avr before " << before << " after " << after);
  CHECK(r.result.summary["e_avr_initial"].get<double>() == Approx(before).epsilon(1e-9));
  CHECK(r.result.summary["e_avr_final"].get<double>() == Approx(after).epsilon(1e-9));
  CHECK(after <= 0.5 * before);
  // The history only falls (the best mesh is kept).
  const auto& h = r.result.summary["e_avr_per_iteration"];
  const int accepted = r.result.summary["iterations"].get<int>();
  REQUIRE(accepted >= 1);
  for (int i = 1; i <= accepted; ++i) CHECK(h[i].get<double>() < h[i - 1].get<double>());
}

TEST_CASE("block: the mesh comes onto the true edges and the sharp vertices end near them", "[sharpen][block]") {
  const BlockRun& r = block_run();
  // The true edge lines to the mesh: the rounding leaves them rho (sqrt 2 - 1) ~ 0.83 delta away.
  const std::vector<Vec3> edges = block_edge_points(0.01);
  const double edge_before = point_errors(edges, r.start).e_avr;
  const double edge_after = point_errors(edges, r.result.mesh).e_avr;
  // The moved (sharp) vertices: where they ended against the edge lines.
  REQUIRE(!r.result.sharp_vertices.empty());
  double sharp_mean = 0.0;
  for (const int v : r.result.sharp_vertices) sharp_mean += distance_to_block_edges(r.result.mesh.vertices[v]);
  sharp_mean /= static_cast<double>(r.result.sharp_vertices.size());
  std::cout << "edge lines to mesh: before " << edge_before << " after " << edge_after
            << "; sharp vertices to edge lines: mean " << sharp_mean << " (delta " << kDelta << ")\n";
  CHECK(edge_after < 0.5 * edge_before);
  CHECK(edge_after < 0.5 * kDelta);
  // Sharp vertices lie within the rounded strip (half-width rho = 2 delta) around the edges, not beyond.
  CHECK(sharp_mean < kDelta);
  // And on the true surface: the moved vertices fit the block.
  const MeshDistance truth(r.truth);
  double on_surface = 0.0;
  for (const int v : r.result.sharp_vertices) on_surface += truth.closest(r.result.mesh.vertices[v]).distance;
  on_surface /= static_cast<double>(r.result.sharp_vertices.size());
  INFO("sharp vertices to the true surface: mean " << on_surface);
  CHECK(on_surface < 0.25 * kDelta);
}

TEST_CASE("block: no triangle flips and the mesh stays watertight with genus 1", "[sharpen][block]") {
  const BlockRun& r = block_run();
  const MeshStats s = mesh_stats(r.result.mesh);
  CHECK(s.watertight);
  CHECK(s.components == 1);
  CHECK(s.genus == Approx(1.0));
  // Orientation against the start: every surviving triangle against the triangle it was in the input
  // (face_origin; near an edge a triangle turns by about 45 degrees, a flip by more than 90).
  REQUIRE(r.result.face_origin.size() == r.result.mesh.faces.size());
  std::size_t flipped = 0, checked = 0;
  for (std::size_t f = 0; f < r.result.mesh.faces.size(); ++f) {
    const int g = r.result.face_origin[f];
    if (g < 0 || g >= static_cast<int>(r.start.faces.size())) {
      ++flipped;  // counted as a failure: every output face must come from an input face
      continue;
    }
    const Face& t = r.result.mesh.faces[f];
    const Face& t0 = r.start.faces[g];
    const auto& V = r.result.mesh.vertices;
    const auto& V0 = r.start.vertices;
    const Vec3 n = (V[t[1]] - V[t[0]]).cross(V[t[2]] - V[t[0]]);
    const Vec3 n0 = (V0[t0[1]] - V0[t0[0]]).cross(V0[t0[2]] - V0[t0[0]]);
    ++checked;
    if (n.dot(n0) <= 0.0) ++flipped;
  }
  INFO(flipped << " of " << checked << " triangles flipped");
  CHECK(flipped == 0);
}

TEST_CASE("block: only vertices near the edges are detected as sharp", "[sharpen][block]") {
  const BlockRun& r = block_run();
  const std::size_t detected = r.result.summary["sharp_vertices"].get<std::size_t>();
  CHECK(detected > 0);
  CHECK(detected < r.start.vertices.size() / 5);
  // Every moved vertex is near an edge line: within the rounded strip (2 delta) plus the two rings the
  // normal-variation measure looks at. (Positions, not ids: the degenerate removal renumbers vertices.)
  // Flat-face vertices farther away are well fitted and must not move.
  double worst = 0.0;
  for (const int v : r.result.sharp_vertices) worst = std::max(worst, distance_to_block_edges(r.result.mesh.vertices[v]));
  INFO("farthest moved vertex from an edge line: " << worst);
  CHECK(worst < 4 * kDelta);
}
