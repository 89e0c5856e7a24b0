// Combinatorial and quality statistics of a triangle mesh (docs/design.md §5, "Mesh").
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

#include "framework/core/connected_components.hpp"
#include "framework/core/error.hpp"
#include "framework/core/mesh_adjacency.hpp"
#include "framework/core/union_find.hpp"
#include "framework/metrics/metrics.hpp"

namespace dtsl {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = 3.14159265358979323846;

bool repeated_index(const Face& t) { return t[0] == t[1] || t[1] == t[2] || t[0] == t[2]; }

// The triangle's smallest angle in degrees; 0 for a zero-length edge (atan2(0, 0) = 0).
double min_angle_deg(const Vec3& a, const Vec3& b, const Vec3& c) {
  const auto angle = [](const Vec3& u, const Vec3& v) { return std::atan2(u.cross(v).norm(), u.dot(v)); };
  const double m = std::min({angle(b - a, c - a), angle(c - b, a - b), angle(a - c, b - c)});
  return m * 180.0 / kPi;
}

// Zero area up to the rounding of the cross product, which is relative to the squared edge lengths.
bool zero_area(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double longest2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return (b - a).cross(c - a).norm() <= 1e-12 * longest2;
}

// Every face, degenerate ones included (their smallest angle is 0).
void quality(const TriangleMesh& mesh, MeshStats& s) {
  std::vector<double> min_angles;
  min_angles.reserve(mesh.faces.size());
  for (const Face& t : mesh.faces) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const bool degenerate = repeated_index(t) || zero_area(a, b, c);
    s.degenerate_faces += degenerate ? 1 : 0;
    min_angles.push_back(repeated_index(t) ? 0.0 : min_angle_deg(a, b, c));
  }
  if (min_angles.empty()) {
    s.min_angle_deg = s.min_angle_p01_deg = s.min_angle_mean_deg = kNaN;
    return;
  }
  s.min_angle_mean_deg = std::accumulate(min_angles.begin(), min_angles.end(), 0.0) / min_angles.size();
  s.min_angle_deg = *std::min_element(min_angles.begin(), min_angles.end());
  // Nearest-rank percentile: the smallest value with at least 1 % of the faces at or below it.
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.01 * min_angles.size()));
  const auto nth = min_angles.begin() + static_cast<long>(rank > 0 ? rank - 1 : 0);
  std::nth_element(min_angles.begin(), nth, min_angles.end());
  s.min_angle_p01_deg = *nth;
}

void validate_vertices(const TriangleMesh& mesh) {
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    if (!mesh.vertices[v].allFinite())
      throw AlgorithmError("mesh statistics: vertex " + std::to_string(v) + " is not finite");
}

// Corners (face, vertex) joined across every shared edge: the corners of one vertex then fall into one
// class per fan, so more than one class marks a non-manifold vertex (a bow tie) that no edge count can
// see. Cost: one union-find over 3F corners.
std::size_t nonmanifold_vertices(const TriangleMesh& mesh, const MeshEdges& edges) {
  const auto corner = [&](int f, int v) {
    const Face& t = mesh.faces[f];
    return static_cast<std::size_t>(3 * f + (t[0] == v ? 0 : t[1] == v ? 1 : 2));
  };
  UnionFind fans(3 * mesh.faces.size());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const int u = edges.ends[e][0], v = edges.ends[e][1], first = edges.faces[edges.first_face[e]];
    for (std::size_t j = edges.first_face[e] + 1; j < edges.first_face[e + 1]; ++j) {
      fans.unite(corner(first, u), corner(edges.faces[j], u));
      fans.unite(corner(first, v), corner(edges.faces[j], v));
    }
  }
  std::vector<std::pair<int, std::size_t>> vertex_fan;  // (vertex, fan class) of every corner
  vertex_fan.reserve(3 * mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& t = mesh.faces[f];
    if (repeated_index(t)) continue;
    for (int k = 0; k < 3; ++k) vertex_fan.emplace_back(t[k], fans.find(3 * f + k));
  }
  std::sort(vertex_fan.begin(), vertex_fan.end());
  vertex_fan.erase(std::unique(vertex_fan.begin(), vertex_fan.end()), vertex_fan.end());
  std::size_t count = 0;
  for (std::size_t j = 1; j < vertex_fan.size(); ++j)
    if (vertex_fan[j].first == vertex_fan[j - 1].first &&
        (j < 2 || vertex_fan[j - 2].first != vertex_fan[j].first))  // count each vertex once
      ++count;
  return count;
}

}  // namespace

MeshStats mesh_stats(const TriangleMesh& mesh) {
  validate_vertices(mesh);
  const MeshEdges edges = mesh_edges(mesh, "mesh statistics");  // checks the indices
  MeshStats s;
  s.vertices = mesh.vertices.size();
  s.faces = mesh.faces.size();
  quality(mesh, s);

  // ---- topology: faces with three distinct indices ----------------------------------------------
  std::vector<Face> faces;
  for (const Face& t : mesh.faces)
    if (!repeated_index(t)) faces.push_back(t);
  for (std::size_t e = 0; e < edges.size(); ++e) {
    s.boundary_edges += edges.boundary(e) ? 1 : 0;
    s.nonmanifold_edges += edges.nonmanifold(e) ? 1 : 0;
  }
  s.nonmanifold_vertices = nonmanifold_vertices(mesh, edges);
  const VertexComponents components = vertex_components(mesh.vertices.size(), faces);
  s.components = components.count;
  const std::vector<int> valence = edges.valences(mesh.vertices.size());
  const std::vector<char> on_boundary = edges.boundary_vertices(mesh.vertices.size());
  std::size_t used_vertices = 0, interior = 0, interior_valence6 = 0;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    if (components.label[v] < 0) continue;
    ++used_vertices;
    if (!on_boundary[v]) {
      ++interior;
      interior_valence6 += valence[v] == 6 ? 1 : 0;
    }
  }
  s.valence6_fraction = interior > 0 ? static_cast<double>(interior_valence6) / interior : kNaN;
  s.euler_characteristic =
      static_cast<int>(used_vertices) - static_cast<int>(edges.size()) + static_cast<int>(faces.size());
  s.watertight = !faces.empty() && s.boundary_edges == 0 && s.nonmanifold_edges == 0 && s.nonmanifold_vertices == 0;
  // Each closed component has chi_i = 2 - 2 g_i, so the total genus is (2 C - chi) / 2.
  s.genus = s.watertight ? (2.0 * static_cast<double>(s.components) - s.euler_characteristic) / 2.0 : kNaN;
  return s;
}

}  // namespace dtsl
