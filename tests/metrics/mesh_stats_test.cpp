#include <catch2/catch.hpp>

#include <cmath>

#include "framework/core/error.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/metrics/message_matcher.hpp"
#include "tests/metrics/shapes.hpp"

using namespace dtsl;

TEST_CASE("mesh_stats of closed genus-0 meshes", "[metrics][stats]") {
  const MeshStats tet = mesh_stats(test::tetrahedron());
  CHECK(tet.vertices == 4);
  CHECK(tet.faces == 4);
  CHECK(tet.euler_characteristic == 2);
  CHECK(tet.watertight);
  CHECK(tet.components == 1);
  CHECK(tet.genus == 0.0);
  CHECK(tet.boundary_edges == 0);
  CHECK(tet.nonmanifold_edges == 0);
  CHECK(tet.nonmanifold_vertices == 0);
  CHECK(tet.min_angle_deg == Approx(45.0));  // the right isosceles faces
  CHECK(tet.min_angle_mean_deg == Approx((3 * 45.0 + 60.0) / 4));
  CHECK(tet.valence6_fraction == 0.0);  // every vertex has valence 3
  CHECK(tet.degenerate_faces == 0);

  const MeshStats cube = mesh_stats(test::cube());
  CHECK(cube.vertices == 8);
  CHECK(cube.faces == 12);
  CHECK(cube.euler_characteristic == 2);
  CHECK(cube.genus == 0.0);
  CHECK(cube.watertight);
  CHECK(cube.min_angle_deg == Approx(45.0));

  const MeshStats sphere = mesh_stats(test::icosphere(3));
  CHECK(sphere.genus == 0.0);
  CHECK(sphere.watertight);
  // 12 valence-5 vertices, all others valence 6.
  CHECK(sphere.valence6_fraction == Approx((sphere.vertices - 12.0) / sphere.vertices));
}

TEST_CASE("mesh_stats of a torus grid has genus 1 and valence 6 everywhere", "[metrics][stats]") {
  const MeshStats s = mesh_stats(test::torus(1.0, 0.3, 20, 10));
  CHECK(s.vertices == 200);
  CHECK(s.faces == 400);
  CHECK(s.euler_characteristic == 0);
  CHECK(s.watertight);
  CHECK(s.components == 1);
  CHECK(s.genus == 1.0);
  CHECK(s.valence6_fraction == 1.0);
}

TEST_CASE("mesh_stats counts components and sums the genus", "[metrics][stats]") {
  TriangleMesh m = test::cube();
  test::append(m, test::cube(Vec3(3, 0, 0), Vec3(4, 1, 1)));
  test::append(m, test::torus(1.0, 0.3, 12, 8));
  const MeshStats s = mesh_stats(m);
  CHECK(s.components == 3);
  CHECK(s.euler_characteristic == 4);
  CHECK(s.watertight);
  CHECK(s.genus == 1.0);

  // An unreferenced vertex is not a component.
  m.vertices.push_back({9, 9, 9});
  CHECK(mesh_stats(m).components == 3);
  CHECK(mesh_stats(m).vertices == m.vertices.size());
}

TEST_CASE("mesh_stats of an open mesh", "[metrics][stats]") {
  TriangleMesh m = test::cube();
  m.faces.pop_back();
  m.faces.pop_back();  // remove one side
  const MeshStats s = mesh_stats(m);
  CHECK(s.boundary_edges == 4);
  CHECK_FALSE(s.watertight);
  CHECK(std::isnan(s.genus));
  CHECK(s.euler_characteristic == 1);  // a disc
  CHECK(s.components == 1);

  const MeshStats square = mesh_stats(test::rectangle(0, 1, 0, 1));
  CHECK(square.boundary_edges == 4);
  CHECK(std::isnan(square.valence6_fraction));  // no interior vertex
}

TEST_CASE("mesh_stats finds non-manifold edges and vertices", "[metrics][stats]") {
  // Three triangles on the edge (0, 1).
  TriangleMesh fin;
  fin.vertices = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}};
  fin.faces = {{{0, 1, 2}}, {{1, 0, 3}}, {{0, 1, 4}}};
  const MeshStats f = mesh_stats(fin);
  CHECK(f.nonmanifold_edges == 1);
  CHECK(f.boundary_edges == 6);
  CHECK_FALSE(f.watertight);

  // Two closed tetrahedra sharing only a vertex: every edge is manifold, the vertex is not.
  TriangleMesh bowtie = test::tetrahedron();
  TriangleMesh other = test::tetrahedron();
  for (Vec3& v : other.vertices) v = -v;
  test::append(bowtie, other);
  for (Face& t : bowtie.faces)
    for (int& i : t)
      if (i == 4) i = 0;  // glue the second tetrahedron's apex to the first one's
  const MeshStats b = mesh_stats(bowtie);
  CHECK(b.boundary_edges == 0);
  CHECK(b.nonmanifold_edges == 0);
  CHECK(b.nonmanifold_vertices == 1);
  CHECK_FALSE(b.watertight);
  CHECK(std::isnan(b.genus));
  CHECK(b.components == 1);
}

TEST_CASE("mesh_stats counts degenerate faces and their zero angles", "[metrics][stats]") {
  TriangleMesh m = test::tetrahedron();
  m.faces.push_back({{0, 0, 1}});      // repeated index
  m.vertices.push_back({0.5, 0, 0});    // on the edge (0, 1)
  m.faces.push_back({{0, 4, 1}});       // zero area
  const MeshStats s = mesh_stats(m);
  CHECK(s.degenerate_faces == 2);
  CHECK(s.min_angle_deg == 0.0);
  CHECK(s.faces == 6);
}

TEST_CASE("mesh_stats angle percentile uses the nearest rank", "[metrics][stats]") {
  // 200 faces: two slivers, the rest right isosceles. The 1st percentile is the 2nd smallest value.
  TriangleMesh m;
  for (int i = 0; i < 200; ++i) {
    const int o = static_cast<int>(m.vertices.size());
    const double h = i == 0 ? 0.01 : i == 1 ? 0.02 : 1.0;
    m.vertices.push_back({10.0 * i, 0, 0});
    m.vertices.push_back({10.0 * i + 1, 0, 0});
    m.vertices.push_back({10.0 * i, h, 0});
    m.faces.push_back({{o, o + 1, o + 2}});
  }
  const MeshStats s = mesh_stats(m);
  CHECK(s.min_angle_deg == Approx(std::atan(0.01) * 180 / M_PI));
  CHECK(s.min_angle_p01_deg == Approx(std::atan(0.02) * 180 / M_PI));
  CHECK(s.components == 200);
}

TEST_CASE("mesh_stats of an empty mesh and bad meshes", "[metrics][stats][errors]") {
  const MeshStats e = mesh_stats(TriangleMesh{});
  CHECK(e.faces == 0);
  CHECK(e.components == 0);
  CHECK_FALSE(e.watertight);
  CHECK(std::isnan(e.min_angle_deg));
  CHECK(std::isnan(e.genus));

  TriangleMesh bad = test::tetrahedron();
  bad.faces[3][2] = 4;
  CHECK_THROWS_MATCHES(mesh_stats(bad), AlgorithmError,
                       test::MessageContains({"face 3", "index 4"}));
  bad = test::tetrahedron();
  bad.vertices[1].y() = std::numeric_limits<double>::infinity();
  CHECK_THROWS_MATCHES(mesh_stats(bad), AlgorithmError, test::MessageContains({"vertex 1"}));
}

TEST_CASE("MeshStats to_json writes NaN as null", "[metrics][json]") {
  TriangleMesh m = test::rectangle(0, 1, 0, 1);
  const nlohmann::json j = to_json(mesh_stats(m));
  CHECK(j.at("genus").is_null());
  CHECK(j.at("valence6_fraction").is_null());
  CHECK(j.at("watertight") == false);
  CHECK(j.at("boundary_edges") == 4);
  CHECK(j.at("min_angle_deg").get<double>() == Approx(45.0));
  const nlohmann::json t = to_json(mesh_stats(test::torus(1, 0.3, 8, 6)));
  CHECK(t.at("genus").get<double>() == 1.0);
  CHECK(t.at("nonmanifold_vertices") == 0);
}
