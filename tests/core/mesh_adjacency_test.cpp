// The shared mesh connectivity (mesh_adjacency.hpp) and components (connected_components.hpp):
// properties on small closed, open, disjoint and non-manifold meshes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "framework/core/connected_components.hpp"
#include "framework/core/error.hpp"
#include "framework/core/mesh_adjacency.hpp"

using namespace dtsl;

namespace {

TriangleMesh tetrahedron(const Vec3& offset = Vec3::Zero()) {
  TriangleMesh m;
  m.vertices = {offset + Vec3(0, 0, 0), offset + Vec3(1, 0, 0), offset + Vec3(0, 1, 0), offset + Vec3(0, 0, 1)};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  return m;
}

TriangleMesh icosahedron() {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  TriangleMesh m;
  m.vertices = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  m.faces = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4},  {3, 4, 2},  {3, 2, 6},  {3, 6, 8},
             {3, 8, 9},  {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7},  {9, 8, 1}};
  return m;
}

std::size_t count_edges(const MeshEdges& e, bool (MeshEdges::*test)(std::size_t) const) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < e.size(); ++i) n += (e.*test)(i) ? 1 : 0;
  return n;
}

}  // namespace

TEST_CASE("a closed tetrahedron: 6 edges of 2 faces, no boundary, one component", "[core][mesh]") {
  const TriangleMesh tet = tetrahedron();
  const MeshAdjacency adj = mesh_adjacency(tet);
  CHECK(adj.edges.size() == 6);
  for (std::size_t e = 0; e < adj.edges.size(); ++e) CHECK(adj.edges.face_count(e) == 2);
  CHECK(count_edges(adj.edges, &MeshEdges::boundary) == 0);
  CHECK(count_edges(adj.edges, &MeshEdges::nonmanifold) == 0);
  for (int v = 0; v < 4; ++v) {
    CHECK(adj.vertex_faces[v].size() == 3);
    CHECK(adj.vertex_neighbours[v].size() == 3);
  }
  const VertexComponents c = vertex_components(tet);
  CHECK(c.count == 1);
  CHECK(std::all_of(c.label.begin(), c.label.end(), [](int l) { return l == 0; }));
}

TEST_CASE("two disjoint tetrahedra are two components, numbered by their smallest vertex", "[core][mesh]") {
  TriangleMesh two = tetrahedron(Vec3(5, 0, 0));
  const TriangleMesh second = tetrahedron();
  for (const Face& f : second.faces) two.faces.push_back({f[0] + 4, f[1] + 4, f[2] + 4});
  two.vertices.insert(two.vertices.end(), second.vertices.begin(), second.vertices.end());
  two.vertices.push_back(Vec3(9, 9, 9));  // referenced by no face
  const VertexComponents c = vertex_components(two);
  CHECK(c.count == 2);
  CHECK(c.label[0] == 0);
  CHECK(c.label[4] == 1);
  CHECK(c.label[7] == 1);
  CHECK(c.label[8] == -1);
  // The same split from the vertex graph.
  const MeshAdjacency adj = mesh_adjacency(two);
  const auto groups = connected_groups(adj.vertex_neighbours, std::vector<char>(two.vertices.size(), 1));
  REQUIRE(groups.size() == 3);  // the lone vertex is a group of its own
  CHECK(groups[0].size() == 4);
  CHECK(groups[1].size() == 4);
  CHECK(groups[2] == std::vector<int>{8});
}

TEST_CASE("an edge shared by three faces is flagged non-manifold; an open fan has boundary edges", "[core][mesh]") {
  TriangleMesh book;  // three pages on the spine 0-1
  book.vertices = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}};
  book.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const MeshEdges e = mesh_edges(book);
  CHECK(e.size() == 7);
  REQUIRE(count_edges(e, &MeshEdges::nonmanifold) == 1);
  for (std::size_t i = 0; i < e.size(); ++i)
    if (e.nonmanifold(i)) {
      CHECK(e.ends[i] == std::array<int, 2>{0, 1});
      CHECK(e.face_count(i) == 3);
    }
  CHECK(count_edges(e, &MeshEdges::boundary) == 6);
  const std::vector<char> on = e.boundary_vertices(book.vertices.size());
  CHECK(std::count(on.begin(), on.end(), 1) == 5);
}

TEST_CASE("icosahedron rings: every vertex has 5 neighbours and 5 faces; k_ring grows by rings", "[core][mesh]") {
  const TriangleMesh ico = icosahedron();
  const MeshAdjacency adj = mesh_adjacency(ico);
  CHECK(adj.edges.size() == 30);
  for (int v = 0; v < 12; ++v) {
    CHECK(adj.vertex_neighbours[v].size() == 5);
    CHECK(adj.vertex_faces[v].size() == 5);
    CHECK(std::is_sorted(adj.vertex_neighbours[v].begin(), adj.vertex_neighbours[v].end()));
  }
  const std::vector<int> valence = adj.edges.valences(12);
  CHECK(std::all_of(valence.begin(), valence.end(), [](int d) { return d == 5; }));
  CHECK(k_ring(adj, 0, 0) == std::vector<int>{0});
  CHECK(k_ring(adj, 0, 1).size() == 6);
  CHECK(k_ring(adj, 0, 2).size() == 11);  // all but the antipode
  CHECK(k_ring(adj, 0, 3).size() == 12);
}

TEST_CASE("misoriented_edges: 0 on a consistently oriented tetrahedron, the 3 edges of one flipped face", "[core][mesh]") {
  TriangleMesh tet = tetrahedron();
  CHECK(misoriented_edges(tet, mesh_edges(tet)) == 0);
  std::swap(tet.faces[2][1], tet.faces[2][2]);
  CHECK(misoriented_edges(tet, mesh_edges(tet)) == 3);
}

TEST_CASE("a face with a repeated corner is no edge's face but stays in the vertex's fan", "[core][mesh]") {
  TriangleMesh m = tetrahedron();
  m.faces.push_back({0, 0, 1});
  const MeshAdjacency adj = mesh_adjacency(m);
  CHECK(adj.edges.size() == 6);
  CHECK(count_edges(adj.edges, &MeshEdges::boundary) == 0);
  CHECK(std::count(adj.vertex_faces[0].begin(), adj.vertex_faces[0].end(), 4) == 2);
}

TEST_CASE("a face index out of range is an AlgorithmError naming the face", "[core][mesh]") {
  TriangleMesh m = tetrahedron();
  m.faces.push_back({0, 1, 7});
  CHECK_THROWS_WITH(mesh_adjacency(m, "test mesh"), Catch::Contains("test mesh: face 4") && Catch::Contains("index 7"));
  m.faces.back() = {0, -1, 2};
  CHECK_THROWS_AS(mesh_edges(m), AlgorithmError);
}

TEST_CASE("connected_groups keeps only members and lists each group depth-first from its smallest vertex", "[core][mesh]") {
  // Path 0-1-2-3-4 with vertex 2 left out: two groups.
  const std::vector<std::vector<int>> path = {{1}, {0, 2}, {1, 3}, {2, 4}, {3}};
  const auto groups = connected_groups(path, {1, 1, 0, 1, 1});
  REQUIRE(groups.size() == 2);
  CHECK(groups[0] == std::vector<int>{0, 1});
  CHECK(groups[1] == std::vector<int>{3, 4});
  CHECK(connected_groups(path, std::vector<char>(5, 0)).empty());
}
