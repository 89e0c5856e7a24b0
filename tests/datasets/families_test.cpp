// The implicit shape families (plate_holes, high_genus, lattice, pair, dumbbell): each ground truth is a
// closed, consistently and outwardly oriented manifold with exactly the components and genus its
// documentation gives, its vertices carry unit normals that agree with its faces, it has the size and
// features its options ask for, and it comes out the same every time.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <map>

#include "framework/config/yaml_options.hpp"
#include "framework/core/connected_components.hpp"
#include "framework/core/error.hpp"
#include "framework/core/mesh_adjacency.hpp"
#include "framework/datasets/dataset.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/datasets/option_errors.hpp"

using namespace dtsl;

namespace {

ShapeData load_shape(const std::string& type, const std::string& yaml) {
  register_dataset_plugins();
  auto shape = shape_sources().create(type, "test");
  apply_yaml(shape->options(), YAML::Load(yaml), "test");
  return shape->load();
}

/// Whether two faces of the mesh cross (CGAL's exact test): a self-intersecting surface bounds no solid,
/// and its genus would say nothing about one.
bool self_intersects(const TriangleMesh& m) {
  using Mesh = CGAL::Surface_mesh<CGAL::Epick::Point_3>;
  Mesh sm;
  std::vector<Mesh::Vertex_index> v;
  for (const Vec3& p : m.vertices) v.push_back(sm.add_vertex({p.x(), p.y(), p.z()}));
  for (const Face& f : m.faces) REQUIRE(sm.add_face(v[f[0]], v[f[1]], v[f[2]]) != Mesh::null_face());
  return CGAL::Polygon_mesh_processing::does_self_intersect(sm);
}

/// Closed manifold without self-intersection, with the given topology, consistently oriented, every component enclosing a positive
/// volume (outward faces), unit vertex normals within 30 degrees of the mean of their faces' normals.
void check_ground_truth(const ShapeData& d, std::size_t components, int genus) {
  REQUIRE(d.mesh);
  CHECK(d.exact);
  const TriangleMesh& m = *d.mesh;
  const MeshStats s = mesh_stats(m);
  CHECK(s.watertight);
  CHECK(s.components == components);
  CHECK(s.genus == genus);
  CHECK(s.degenerate_faces == 0);
  CHECK(s.min_angle_deg > 5.0);  // isotropic remeshing leaves no sliver
  CHECK_FALSE(self_intersects(m));

  CHECK(misoriented_edges(m, mesh_edges(m)) == 0);

  const std::vector<int> label = vertex_components(m).label;
  std::map<int, double> volume;
  std::map<int, Vec3> centre;
  std::map<int, int> count;
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    centre.emplace(label[v], Vec3::Zero());  // Eigen leaves a default-constructed vector uninitialised
    centre[label[v]] += m.vertices[v];
    ++count[label[v]];
  }
  for (auto& [l, c] : centre) c /= count[l];
  std::vector<Vec3> face_sum(m.vertices.size(), Vec3::Zero());
  for (const Face& f : m.faces) {
    const Vec3 o = centre[label[f[0]]];
    const Vec3 a = m.vertices[f[0]] - o, b = m.vertices[f[1]] - o, c = m.vertices[f[2]] - o;
    volume[label[f[0]]] += a.dot(b.cross(c)) / 6.0;
    const Vec3 n = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) face_sum[f[k]] += n;
  }
  CHECK(volume.size() == components);
  for (const auto& [l, v] : volume) CHECK(v > 0.0);

  REQUIRE(m.has_normals());
  std::size_t off = 0;
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    REQUIRE(std::abs(m.normals[v].norm() - 1.0) < 1e-9);
    off += m.normals[v].dot(face_sum[v].normalized()) < std::cos(M_PI / 6) ? 1 : 0;
  }
  CHECK(off == 0);
}

BoundingBox box_of(const ShapeData& d) { return bounding_box(d.mesh->vertices); }

}  // namespace

TEST_CASE("plate_holes: genus = number of holes, plate 2 long, holes where the options put them",
          "[datasets][families]") {
  SECTION("defaults: three holes") {
    const ShapeData d = load_shape("plate_holes", "{}");
    check_ground_truth(d, 1, 3);
    // The extremes of a curved rim fall between vertices: within a sagitta of the true size.
    const BoundingBox b = box_of(d);
    CHECK(b.extent().x() == Approx(2.0).margin(0.005));
    CHECK(b.extent().y() == Approx(1.2).margin(0.005));
    CHECK(b.extent().z() == Approx(0.16).margin(0.005));
    CHECK((b.extent().array() <= Eigen::Array3d(2.0, 1.2, 0.16) + 1e-9).all());
  }
  SECTION("one small hole, thin plate") {
    const ShapeData d = load_shape("plate_holes", "{hole_diameters: [0.05], thickness: 0.1, edge_length: 0.025}");
    check_ground_truth(d, 1, 1);
    // The hole (diameter 0.1 at the centre): no vertex inside its wall's cylinder.
    for (const Vec3& p : d.mesh->vertices) REQUIRE(std::hypot(p.x(), p.y()) > 0.05 - 1e-9);
  }
  SECTION("five holes") {
    const ShapeData d = load_shape("plate_holes", "{hole_diameters: [0.1, 0.12, 0.08, 0.12, 0.1], edge_length: 0.04}");
    check_ground_truth(d, 1, 5);
  }
}

TEST_CASE("high_genus: a rows x columns grid of holes has genus rows * columns", "[datasets][families]") {
  SECTION("defaults: 4 x 6") {
    const ShapeData d = load_shape("high_genus", "{}");
    check_ground_truth(d, 1, 24);
    CHECK(box_of(d).extent().x() == Approx(2.0).margin(0.005));
  }
  SECTION("2 x 3, large holes") {
    check_ground_truth(load_shape("high_genus", "{rows: 2, columns: 3, hole_fraction: 0.7, edge_length: 0.04}"), 1, 6);
  }
}

TEST_CASE("lattice: genus is the cycle rank of its bar graph", "[datasets][families]") {
  SECTION("cubic frame: 12 bars, 8 joints, genus 5") {
    const ShapeData d = load_shape("lattice", "{}");
    check_ground_truth(d, 1, 5);
    // Bar axes span 2; the surface adds a bar radius (0.1 of the cell of 2) on each side, and the
    // fillets of three bars meeting at a corner a little more (at most a third of the blend width 0.1).
    const BoundingBox b = box_of(d);
    for (int k = 0; k < 3; ++k) {
      CHECK(b.extent()[k] > 2.4 - 0.005);
      CHECK(b.extent()[k] < 2.4 + 2 * 0.1 / 3);
    }
  }
  SECTION("flat 3 x 3 grid: genus 9") {
    check_ground_truth(load_shape("lattice", "{cells: [3, 3, 0], bar_radius: 0.15, edge_length: 0.03}"), 1, 9);
  }
  SECTION("2 x 1 x 1: genus 9") {
    check_ground_truth(load_shape("lattice", "{cells: [2, 1, 1], edge_length: 0.04}"), 1, 9);
  }
  SECTION("thin bars at the edge-length bound (half the bar radius): genus 5") {
    check_ground_truth(load_shape("lattice", "{bar_radius: 0.05, edge_length: 0.05}"), 1, 5);
  }
}

TEST_CASE("pair: two components with the requested gap between them", "[datasets][families]") {
  for (const char* object : {"sphere", "torus", "box"}) {
    const double gap = 0.05;
    const ShapeData d = load_shape("pair", std::string("{object: ") + object + ", gap: 0.05, edge_length: 0.04}");
    INFO(object);
    check_ground_truth(d, 2, std::string(object) == "torus" ? 2 : 0);
    // Along x the pair spans 2; the facing surfaces are gap * s apart, s = 2 / (2 + gap).
    CHECK(box_of(d).extent().x() == Approx(2.0).margin(0.005));
    double inner_left = -1e9, inner_right = 1e9;
    for (const Vec3& p : d.mesh->vertices) (p.x() < 0 ? inner_left : inner_right) =
                                               p.x() < 0 ? std::max(inner_left, p.x()) : std::min(inner_right, p.x());
    const double expected = gap * 2.0 / (2.0 + gap);
    CHECK(inner_right - inner_left >= expected - 1e-9);
    CHECK(inner_right - inner_left == Approx(expected).margin(0.01));
  }
}

TEST_CASE("dumbbell: one genus-0 component, 2 long, a neck of the requested radius", "[datasets][families]") {
  const ShapeData d = load_shape("dumbbell", "{}");
  check_ground_truth(d, 1, 0);
  CHECK(box_of(d).extent().x() == Approx(2.0).margin(0.005));
  // At the neck's middle (x = 0) every vertex is at the neck radius 0.15 * 2 / 5 from the axis.
  std::size_t at_middle = 0;
  for (const Vec3& p : d.mesh->vertices)
    if (std::abs(p.x()) < 0.02) {
      ++at_middle;
      CHECK(std::hypot(p.y(), p.z()) == Approx(0.06).margin(1e-6));
    }
  CHECK(at_middle > 0);
  SECTION("a thin neck at the edge-length bound (half its radius) stays one component") {
    check_ground_truth(load_shape("dumbbell", "{neck_radius: 0.1, neck_length: 0.5, edge_length: 0.02}"), 1, 0);
  }
}

TEST_CASE("implicit families are deterministic", "[datasets][families]") {
  const ShapeData a = load_shape("lattice", "{cells: [2, 1, 1], edge_length: 0.04}");
  const ShapeData b = load_shape("lattice", "{cells: [2, 1, 1], edge_length: 0.04}");
  REQUIRE(a.mesh->vertices.size() == b.mesh->vertices.size());
  REQUIRE(a.mesh->faces == b.mesh->faces);
  for (std::size_t i = 0; i < a.mesh->vertices.size(); ++i) REQUIRE(a.mesh->vertices[i] == b.mesh->vertices[i]);
}

TEST_CASE("implicit family options are checked, naming the key", "[datasets][families][bad]") {
  const auto expect = test::expect_shape_option_error;
  expect("plate_holes", "{hole_diameters: []}", "s.hole_diameters: must list 1 to 5 diameters, got 0");
  expect("plate_holes", "{hole_diameters: [0.1, 0.1, 0.1, 0.1, 0.1, 0.1]}", "s.hole_diameters: must list 1 to 5");
  expect("plate_holes", "{hole_diameters: [0.5]}", "s.hole_diameters: each must be in [0.05, 0.4]");
  expect("plate_holes", "{hole_diameters: [0.3, 0.3, 0.3]}", "s.hole_diameters: leave a wall of");
  expect("plate_holes", "{thickness: 0.8}", "s.thickness: must be at most half the width");
  expect("plate_holes", "{corner_radius: 0.01}", "s.corner_radius: must be in [thickness / 2, width / 2]");
  expect("plate_holes", "{rim_blend: 0}", "s.rim_blend: must be in (0, thickness / 2");
  expect("plate_holes", "{edge_length: 0.1}", "s.edge_length: must be at most a quarter of the thickness");
  expect("high_genus", "{rows: 0}", "s.rows: must be in [1, 12], got 0");
  expect("high_genus", "{rows: 7, columns: 6}", "s.rows: must be at most columns");
  expect("high_genus", "{hole_fraction: 0.9}", "s.hole_fraction: must be in [0.2, 0.8], got 0.9");
  expect("high_genus", "{edge_length: 0.0001}", "s.edge_length: too small for this plate");
  expect("lattice", "{cells: [1, 1]}", "s.cells: must have 3 entries, got 2");
  expect("lattice", "{cells: [1.5, 1, 1]}", "s.cells: each entry must be an integer in [0, 6], got 1.5");
  expect("lattice", "{cells: [0, 0, 3]}", "s.cells: at most one entry may be 0");
  expect("lattice", "{bar_radius: 0.4}", "s.bar_radius: must be in [0.02, 0.3], got 0.4");
  expect("lattice", "{edge_length: 0.2}", "s.edge_length: must be at most half the bar radius");
  expect("pair", "{object: cone}", "s.object: must be one of");
  expect("pair", "{gap: 0}", "s.gap: must be in [0.001, 2], got 0");
  expect("pair", "{edge_length: 0.1}", "s.edge_length: must be in [0.003, 0.05], got 0.1");
  expect("dumbbell", "{neck_radius: 0.9}", "s.neck_radius: must be in [0.02, 0.7], got 0.9");
  expect("dumbbell", "{edge_length: 0.05}", "s.edge_length: must be at most half the neck's radius");
  expect("dumbbell", "{blend: 0}", "s.blend: must be in [0.01, 0.5], got 0");
  expect("lattice", "{blend: 0}", "s.blend: must be in [0.1, 1], got 0");
  expect("dumbbell", "{neck: 1}", "s.neck: unknown key");
}
