// The T-mesh kept for the figure of points + T-mesh (the paper's Fig. 1a): the edges of exactly the
// leaves holding given samples (a dtsl run: the data and the zero set); a dtsl run writes them as
// tmesh.obj, on octree cell edges, inside the domain and near the data; the report's reader reads the
// T-mesh files of save_level_set too.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include "algorithms/evolution/evolution.hpp"
#include "algorithms/method/dtsl_pipeline.hpp"
#include "algorithms/method/tmesh_lines.hpp"
#include "algorithms/tspline/tspline_io.hpp"
#include "framework/datasets/dataset.hpp"
#include "framework/io/io.hpp"
#include "framework/pipeline/line_obj.hpp"
#include "framework/pipeline/run_one.hpp"

using namespace dtsl;
namespace fs = std::filesystem;

namespace {

std::vector<Vec3> sphere_points(int n, double r) {
  std::vector<Vec3> p;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double y = 1.0 - 2.0 * (i + 0.5) / n, s = std::sqrt(1.0 - y * y);
    p.push_back(r * Vec3(s * std::cos(golden * i), y, s * std::sin(golden * i)));
  }
  return p;
}

using Key = std::array<long long, 6>;  // a segment by its end points on the finest lattice, smaller end first

Key key(const Octree& t, const Segment& s) {
  std::array<long long, 3> a, b;
  for (int c = 0; c < 3; ++c) {
    a[c] = std::llround((s[0][c] - t.domain_min()[c]) / t.unit());
    b[c] = std::llround((s[1][c] - t.domain_min()[c]) / t.unit());
  }
  if (b < a) std::swap(a, b);
  return {a[0], a[1], a[2], b[0], b[1], b[2]};
}

/// True if the segment lies in the closed boundary of the box (on one of its faces).
bool on_boundary(const BoundingBox& box, const Segment& s, double tol) {
  for (const Vec3& p : s)
    if ((p.array() < box.min.array() - tol).any() || (p.array() > box.max.array() + tol).any()) return false;
  for (int c = 0; c < 3; ++c)
    for (double plane : {box.min[c], box.max[c]})
      if (std::abs(s[0][c] - plane) < tol && std::abs(s[1][c] - plane) < tol) return true;
  return false;
}

}  // namespace

TEST_CASE("tmesh_edges_around: the edges of exactly the leaves holding the samples", "[method][tmesh]") {
  const Octree tree = build_octree(sphere_points(3000, 0.8), TMeshOptions{});
  const std::vector<Vec3> samples = sphere_points(400, 0.8);
  std::set<int> held;
  for (const Vec3& p : samples) held.insert(tree.locate(p));
  const std::vector<Segment> edges = tmesh_edges_around(tree, samples);
  const std::vector<Segment> all = tmesh_edges(tree);
  CHECK(edges.size() < all.size() / 2);  // a shell of the T-mesh, not the whole of it
  std::set<Key> got;
  for (const Segment& e : edges) got.insert(key(tree, e));
  CHECK(got.size() == edges.size());  // each edge once
  const double tol = 1e-9;
  // Every edge of a held leaf is there...
  for (int leaf : held) {
    const Octree::Cell& c = tree.leaf(leaf);
    const int s = tree.cell_size(c.level);
    for (int axis = 0; axis < 3; ++axis)
      for (int k = 0; k < 4; ++k) {
        Int3 a = c.origin;
        a[(axis + 1) % 3] += (k & 1) ? s : 0;
        a[(axis + 2) % 3] += (k & 2) ? s : 0;
        Int3 b = a;
        b[axis] += s;
        CHECK(got.count(key(tree, {tree.point(a), tree.point(b)})));
      }
  }
  // ...and every edge drawn lies on the boundary of a held leaf and is an edge of the T-mesh.
  std::set<Key> tmesh;
  for (const Segment& e : all) tmesh.insert(key(tree, e));
  for (const Segment& e : edges) {
    CHECK(tmesh.count(key(tree, e)));
    bool on_held = false;
    for (int leaf : held) on_held = on_held || on_boundary(tree.leaf_box(leaf), e, tol);
    CHECK(on_held);
  }
  CHECK(tmesh_edges_around(tree, {}).empty());
}

TEST_CASE("the report's line reader reads save_level_set's T-mesh files", "[method][tmesh]") {
  const Octree tree = build_octree(sphere_points(1000, 0.7), TMeshOptions{});
  const fs::path p = fs::temp_directory_path() / ("dtsl_tmesh_" + std::to_string(::getpid()) + ".obj");
  write_tmesh_obj(p.string(), tree);
  const std::vector<Segment> read = read_line_obj(p.string());
  const std::vector<Segment> edges = tmesh_edges(tree);
  REQUIRE(read.size() == edges.size());
  std::set<Key> a, b;
  for (const Segment& e : read) a.insert(key(tree, e));
  for (const Segment& e : edges) b.insert(key(tree, e));
  CHECK(a == b);
  fs::remove(p);
}

TEST_CASE("a dtsl run writes its T-mesh: lines on octree cell edges, inside the domain, near the data",
          "[method][tmesh]") {
  register_dtsl_pipeline();
  register_dataset_plugins();
  DatasetSpec spec = parse_dataset(YAML::Load("{name: s, shape: sphere, sampler: {type: area, count: 1500}}"), "test");
  const Dataset data = build_dataset(spec, 3);
  RunSpec run;
  run.id = "s__dtsl";
  run.dataset_name = run.dataset_key = "s";
  run.pipeline_name = run.pipeline_type = "dtsl";
  run.pipeline = YAML::Load("{name: dtsl, type: dtsl, options: {sharpen: false}}");
  MetricsOptions metrics;
  metrics.samples = 2000;
  const fs::path dir = fs::temp_directory_path() / ("dtsl_tmesh_run_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const nlohmann::json record = execute_run(run, data, metrics, 1, dir.string(), FilesFrame::normalised);
  INFO(record.dump(1).substr(0, 2000));
  REQUIRE(record.value("status", "") == "ok");
  const nlohmann::json& tl = record["stages"][0];
  CHECK(tl.value("name", "") == "TL");
  REQUIRE(tl.value("lines_file", "") == "tmesh.obj");
  CHECK(tl.value("lines_label", "") == "T-mesh");
  const std::vector<Segment> lines = read_line_obj((dir / "tmesh.obj").string());
  REQUIRE(!lines.empty());
  CHECK(tl.value("lines_segments", 0) == int(lines.size()));

  // The octree's lattice (default T-mesh options): domain [-1-margin, 1+margin]^3, 2^max_depth cells a side.
  const TMeshOptions t = EvolutionOptions{}.tmesh;
  const double lo = -1.0 - t.margin, side = 2.0 + 2.0 * t.margin, unit = side / (1 << t.max_depth);
  const double coarsest = side / (1 << t.min_depth);
  BoundingBox surface = bounding_box(read_mesh((dir / "stage_MI.ply").string()).vertices);
  for (const Vec3& p : data.points.points) surface.extend(p);
  for (const Segment& s : lines) {
    INFO("segment (" << s[0].transpose() << ") - (" << s[1].transpose() << ")");
    std::array<double, 3> a, b;
    int moving = 0;
    for (int c = 0; c < 3; ++c) {
      a[c] = (s[0][c] - lo) / unit, b[c] = (s[1][c] - lo) / unit;
      CHECK(std::abs(a[c] - std::round(a[c])) < 1e-6);  // end points on the lattice
      CHECK(std::abs(b[c] - std::round(b[c])) < 1e-6);
      CHECK((a[c] > -1e-6 && a[c] < (1 << t.max_depth) + 1e-6));  // inside the domain
      CHECK((b[c] > -1e-6 && b[c] < (1 << t.max_depth) + 1e-6));
      moving += std::abs(a[c] - b[c]) > 0.5;
    }
    CHECK(moving == 1);  // axis-aligned
    // A cell edge: its length is a cell side 2^k, and its end points are corners of a cell of that side.
    const long long length = std::llround((s[1] - s[0]).norm() / unit);
    CHECK(length > 0);
    CHECK((length & (length - 1)) == 0);
    for (int c = 0; c < 3; ++c) CHECK(std::llround(std::min(a[c], b[c])) % length == 0);
    // Near the data and the zero set: within a coarsest cell of their box.
    for (const Vec3& p : s) {
      CHECK(((p - surface.min).array() > -coarsest - 1e-9).all());
      CHECK(((surface.max - p).array() > -coarsest - 1e-9).all());
    }
  }
  fs::remove_all(dir);
}
