// Shape sources: every synthetic shape is a closed, edge-manifold, outward-oriented surface with the
// topology it claims; the smooth ones lie on their analytic surface with its normals; the block has its
// sharp edges where a CAD part has them and nowhere else.
#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <algorithm>

#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "framework/core/mesh_adjacency.hpp"
#include "framework/datasets/dataset.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/datasets/option_errors.hpp"

using namespace dtsl;

namespace {

ShapeData load_shape(const std::string& type, const std::string& yaml = "{}") {
  register_dataset_plugins();
  auto shape = shape_sources().create(type, "test");
  apply_yaml(shape->options(), YAML::Load(yaml), "test");
  return shape->load();
}

double signed_volume(const TriangleMesh& m) {
  double v = 0;
  for (const Face& f : m.faces) v += m.vertices[f[0]].dot(m.vertices[f[1]].cross(m.vertices[f[2]]));
  return v / 6.0;
}

void check_closed(const TriangleMesh& m, std::size_t components, double genus) {
  const MeshStats s = mesh_stats(m);  // what the experiments report
  CHECK(s.boundary_edges == 0);
  CHECK(s.nonmanifold_edges == 0);
  CHECK(s.watertight);
  CHECK(misoriented_edges(m, mesh_edges(m)) == 0);
  CHECK(s.components == components);
  CHECK(s.genus == genus);
  CHECK(signed_volume(m) > 0.0);  // faces oriented outward
  CHECK(s.degenerate_faces == 0);
  for (const Face& f : m.faces) {
    const Vec3 c = (m.vertices[f[1]] - m.vertices[f[0]]).cross(m.vertices[f[2]] - m.vertices[f[0]]);
    REQUIRE(c.norm() > 0.0);  // no degenerate triangle
  }
}

void check_unit_normals(const TriangleMesh& m) {
  REQUIRE(m.has_normals());
  for (const Vec3& n : m.normals) REQUIRE(std::abs(n.norm() - 1.0) < 1e-12);
}

}  // namespace

TEST_CASE("sphere: closed genus 0, vertices and normals on the analytic sphere", "[datasets][shapes]") {
  const ShapeData d = load_shape("sphere", "{radius: 2.5, centre: [1, -2, 3], subdivisions: 4}");
  REQUIRE(d.mesh);
  CHECK(d.exact);
  CHECK_FALSE(d.points);
  const TriangleMesh& m = *d.mesh;
  CHECK(m.vertices.size() == 10 * 256 + 2);
  check_closed(m, 1, 0);
  check_unit_normals(m);
  const Vec3 c(1, -2, 3);
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    REQUIRE(std::abs((m.vertices[i] - c).norm() - 2.5) < 1e-12);
    REQUIRE((m.normals[i] - (m.vertices[i] - c) / 2.5).norm() < 1e-12);  // outward radial
  }
}

TEST_CASE("torus: closed genus 1, vertices and normals on the analytic torus", "[datasets][shapes]") {
  const double R = 2.0, r = 0.5;
  const ShapeData d = load_shape("torus", "{R: 2, r: 0.5, major_segments: 96, minor_segments: 24}");
  REQUIRE(d.mesh);
  CHECK(d.exact);
  const TriangleMesh& m = *d.mesh;
  CHECK(m.vertices.size() == 96 * 24);
  check_closed(m, 1, 1);
  check_unit_normals(m);
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    const Vec3& p = m.vertices[i];
    const double rho = std::hypot(p.x(), p.y());
    REQUIRE(std::abs(std::hypot(rho - R, p.z()) - r) < 1e-12);  // (rho - R)^2 + z^2 = r^2
    const Vec3 core(R * p.x() / rho, R * p.y() / rho, 0.0);        // nearest point of the core circle
    REQUIRE((m.normals[i] - (p - core) / r).norm() < 1e-12);
  }
}

TEST_CASE("two_spheres: two closed genus-0 components with the requested gap", "[datasets][shapes]") {
  const ShapeData d = load_shape("two_spheres", "{radius: 1, gap: 0.3, subdivisions: 3}");
  REQUIRE(d.mesh);
  const TriangleMesh& m = *d.mesh;
  check_closed(m, 2, 0);
  check_unit_normals(m);
  const Vec3 left(-1.15, 0, 0), right(1.15, 0, 0);
  double min_gap = 1e9;
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    const Vec3& p = m.vertices[i];
    const Vec3& c = p.x() < 0 ? left : right;
    REQUIRE(std::abs((p - c).norm() - 1.0) < 1e-12);
    REQUIRE((m.normals[i] - (p - c)).norm() < 1e-12);
    if (p.x() > 0) min_gap = std::min(min_gap, p.x() - 0.15);
  }
  CHECK(min_gap == Approx(0.0).margin(1e-12));  // the icosphere has vertices at +-x: gap exactly 0.3
}

TEST_CASE("block: closed genus 1, dense, sharp exactly at the box edges and hole rims", "[datasets][shapes]") {
  const double L = 2.0, W = 1.4, H = 0.8, rh = 0.35, e = 0.03;
  const ShapeData d = load_shape("block");  // the defaults above
  REQUIRE(d.mesh);
  CHECK(d.exact);
  const TriangleMesh& m = *d.mesh;
  check_closed(m, 1, 1);
  check_unit_normals(m);
  INFO("block vertices: " << m.vertices.size() << ", faces: " << m.faces.size());
  CHECK(m.vertices.size() > 10000);
  CHECK(m.vertices.size() < 20000);

  // Every vertex on the boundary of the solid: on a face of the box, or on the hole's cylinder.
  for (const Vec3& p : m.vertices) {
    const bool on_box = std::abs(std::abs(p.x()) - L / 2) < 1e-12 || std::abs(std::abs(p.y()) - W / 2) < 1e-12 ||
                        std::abs(std::abs(p.z()) - H / 2) < 1e-12;
    const bool on_hole = std::abs(std::hypot(p.x(), p.y()) - rh) < 1e-9;
    REQUIRE((on_box || on_hole));
    REQUIRE(std::abs(p.x()) <= L / 2 + 1e-12);
    REQUIRE(std::abs(p.y()) <= W / 2 + 1e-12);
    REQUIRE(std::abs(p.z()) <= H / 2 + 1e-12);
    REQUIRE(std::hypot(p.x(), p.y()) >= rh - 1e-9);
  }

  // Evenly dense: no edge much longer than the target spacing, none much shorter.
  const MeshEdges edges = mesh_edges(m);
  double shortest = 1e9, longest = 0;
  for (const auto& [u, v] : edges.ends) {
    const double len = (m.vertices[u] - m.vertices[v]).norm();
    shortest = std::min(shortest, len);
    longest = std::max(longest, len);
  }
  INFO("edge lengths in [" << shortest << ", " << longest << "], target " << e);
  CHECK(longest < 3.0 * e);
  CHECK(shortest > 0.3 * e);

  // Sharp edges: total length of edges whose faces meet at more than 45 degrees = the 12 box edges
  // plus the two hole rims (polygons inscribed in the circle, so slightly shorter). Every other edge
  // is nearly flat: the hole's facets turn by about 2 pi / (its point count).
  auto normal = [&](int f) {
    const Face& t = m.faces[f];
    return Vec3((m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).normalized());
  };
  double sharp_length = 0, max_soft_angle = 0;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    REQUIRE(edges.face_count(e) == 2);
    const int f0 = edges.faces[edges.first_face[e]], f1 = edges.faces[edges.first_face[e] + 1];
    const double angle = std::acos(std::clamp(normal(f0).dot(normal(f1)), -1.0, 1.0));
    if (angle > M_PI / 4) {
      CHECK(angle == Approx(M_PI / 2).margin(1e-9));  // all the block's edges are right angles
      sharp_length += (m.vertices[edges.ends[e][0]] - m.vertices[edges.ends[e][1]]).norm();
    } else {
      max_soft_angle = std::max(max_soft_angle, angle);
    }
  }
  const double expected = 4 * (L + W + H) + 2 * 2 * M_PI * rh;
  CHECK(sharp_length == Approx(expected).epsilon(0.005));
  CHECK(max_soft_angle < 0.2);  // about 11 degrees

  // Vertex normals: exactly the face normal inside a flat face, radial (towards the axis) on the hole.
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    const Vec3& p = m.vertices[i];
    const Vec3& n = m.normals[i];
    if (std::abs(p.z()) < H / 2 - 1e-9 && std::abs(std::hypot(p.x(), p.y()) - rh) < 1e-9)
      REQUIRE((n - Vec3(-p.x(), -p.y(), 0).normalized()).norm() < 1e-9);
    if (std::abs(p.z() - H / 2) < 1e-12 && std::abs(p.x()) < L / 2 - 1e-9 && std::abs(p.y()) < W / 2 - 1e-9 &&
        std::hypot(p.x(), p.y()) > rh + 1e-9)
      REQUIRE((n - Vec3(0, 0, 1)).norm() < 1e-12);
  }
}

TEST_CASE("block: other proportions stay closed genus 1", "[datasets][shapes]") {
  // A long thin plate with a small hole (several halvings near the hole), a cube with a large one, a
  // pin-hole (its circle keeps at least 16 points), and a coarse block.
  for (const char* yaml : {"{length: 4, width: 1, height: 0.3, hole_radius: 0.1, edge_length: 0.05}",
                           "{hole_radius: 0.005, edge_length: 0.05}",
                           "{length: 1, width: 1, height: 1, hole_radius: 0.4, edge_length: 0.05}",
                           "{edge_length: 0.2}"}) {
    INFO(yaml);
    const ShapeData d = load_shape("block", yaml);
    check_closed(*d.mesh, 1, 1);
    check_unit_normals(*d.mesh);
    const double rh = YAML::Load(yaml)["hole_radius"].as<double>(0.35);
    const double top = bounding_box(d.mesh->vertices).max.z();
    std::size_t on_rim = 0;  // vertices of the hole's top rim
    for (const Vec3& p : d.mesh->vertices)
      on_rim += std::abs(std::hypot(p.x(), p.y()) - rh) < 1e-9 && p.z() == top ? 1 : 0;
    CHECK(on_rim >= 16);
  }
}

TEST_CASE("shape options are checked, naming the field", "[datasets][shapes][bad]") {
  const auto expect = test::expect_shape_option_error;
  expect("sphere", "{radius: 0}", "s.radius: must be positive, got 0");
  expect("sphere", "{centre: [1, 2]}", "s.centre: must have 3 entries, got 2");
  expect("sphere", "{subdivisions: 12}", "s.subdivisions: must be in [0, 8], got 12");
  expect("torus", "{R: 1, r: 1.5}", "s.r: must be smaller than R");
  expect("two_spheres", "{gap: -1}", "s.gap: must be positive, got -1");
  expect("block", "{hole_radius: 0.7}", "s.hole_radius: must be at most 0.4 * min(length, width)");
  expect("block", "{edge_length: 0.0001}", "s.edge_length: too small for this block");
  expect("block", "{radius: 1}", "s.radius: unknown key");
  expect("cgal_model", "{model: ../etc/passwd}", "s.model: must be a bare model name");
  expect("file", "{}", "s.points: is required unless ground_truth is given");
}
