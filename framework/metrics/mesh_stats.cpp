// Combinatorial and quality statistics of a triangle mesh (docs/design.md §5, "Mesh").
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

#include "framework/core/error.hpp"
#include "framework/metrics/metrics.hpp"

namespace dtsl {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = 3.14159265358979323846;

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), std::size_t{0}); }
  std::size_t find(std::size_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];  // path halving
    return x;
  }
  void unite(std::size_t a, std::size_t b) { parent_[find(a)] = find(b); }

 private:
  std::vector<std::size_t> parent_;
};

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

void validate(const TriangleMesh& mesh) {
  const long n = static_cast<long>(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    if (!mesh.vertices[v].allFinite())
      throw AlgorithmError("mesh statistics: vertex " + std::to_string(v) + " is not finite");
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int i : mesh.faces[f])
      if (i < 0 || i >= n)
        throw AlgorithmError("mesh statistics: face " + std::to_string(f) + " has vertex index " +
                             std::to_string(i) + " outside [0, " + std::to_string(n) + ")");
}

}  // namespace

MeshStats mesh_stats(const TriangleMesh& mesh) {
  validate(mesh);
  MeshStats s;
  s.vertices = mesh.vertices.size();
  s.faces = mesh.faces.size();

  // ---- quality: every face, degenerate ones included (their min angle is 0) --------------------
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
  } else {
    s.min_angle_mean_deg = std::accumulate(min_angles.begin(), min_angles.end(), 0.0) / min_angles.size();
    s.min_angle_deg = *std::min_element(min_angles.begin(), min_angles.end());
    // Nearest-rank percentile: the smallest value with at least 1 % of the faces at or below it.
    const std::size_t rank = static_cast<std::size_t>(std::ceil(0.01 * min_angles.size()));
    const auto nth = min_angles.begin() + static_cast<long>(rank > 0 ? rank - 1 : 0);
    std::nth_element(min_angles.begin(), nth, min_angles.end());
    s.min_angle_p01_deg = *nth;
  }

  // ---- topology: faces with three distinct indices ----------------------------------------------
  std::vector<int> faces;  // indices of the topological faces
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    if (!repeated_index(mesh.faces[f])) faces.push_back(static_cast<int>(f));

  // Every (edge, corner slot) once, sorted by edge, so the faces around an edge are contiguous.
  struct EdgeUse {
    std::uint64_t key;
    int face;  // position in `faces`
  };
  std::vector<EdgeUse> uses;
  uses.reserve(3 * faces.size());
  const auto key_of = [](int u, int v) {
    if (u > v) std::swap(u, v);
    return (static_cast<std::uint64_t>(u) << 32) | static_cast<std::uint32_t>(v);
  };
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const Face& t = mesh.faces[faces[i]];
    for (int k = 0; k < 3; ++k) uses.push_back({key_of(t[k], t[(k + 1) % 3]), static_cast<int>(i)});
  }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& a, const EdgeUse& b) {
    return a.key < b.key || (a.key == b.key && a.face < b.face);
  });

  // Corners (face, vertex) joined across every shared edge: the corners of one vertex then fall into
  // one class per fan, so more than one class marks a non-manifold vertex (a bow tie) that no edge
  // count can see. Cost: one union-find over 3F corners.
  const auto corner = [&](int i, int v) {
    const Face& t = mesh.faces[faces[i]];
    return static_cast<std::size_t>(3 * i + (t[0] == v ? 0 : t[1] == v ? 1 : 2));
  };
  UnionFind fans(3 * faces.size());
  std::vector<int> valence(mesh.vertices.size(), 0);
  std::vector<char> on_boundary(mesh.vertices.size(), 0);
  std::size_t edges = 0;
  for (std::size_t begin = 0; begin < uses.size();) {
    std::size_t end = begin;
    while (end < uses.size() && uses[end].key == uses[begin].key) ++end;
    const int u = static_cast<int>(uses[begin].key >> 32), v = static_cast<int>(uses[begin].key & 0xffffffffu);
    const std::size_t count = end - begin;
    ++edges;
    ++valence[u];
    ++valence[v];
    if (count == 1) {
      ++s.boundary_edges;
      on_boundary[u] = on_boundary[v] = 1;
    } else if (count > 2) {
      ++s.nonmanifold_edges;
    }
    for (std::size_t j = begin + 1; j < end; ++j) {
      fans.unite(corner(uses[begin].face, u), corner(uses[j].face, u));
      fans.unite(corner(uses[begin].face, v), corner(uses[j].face, v));
    }
    begin = end;
  }

  std::vector<std::pair<int, std::size_t>> vertex_fan;  // (vertex, fan class) of every corner
  vertex_fan.reserve(3 * faces.size());
  UnionFind components(mesh.vertices.size());
  std::vector<char> referenced(mesh.vertices.size(), 0);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const Face& t = mesh.faces[faces[i]];
    components.unite(t[0], t[1]);
    components.unite(t[1], t[2]);
    for (int k = 0; k < 3; ++k) {
      referenced[t[k]] = 1;
      vertex_fan.emplace_back(t[k], fans.find(3 * i + k));
    }
  }
  std::sort(vertex_fan.begin(), vertex_fan.end());
  vertex_fan.erase(std::unique(vertex_fan.begin(), vertex_fan.end()), vertex_fan.end());
  for (std::size_t j = 1; j < vertex_fan.size(); ++j)
    if (vertex_fan[j].first == vertex_fan[j - 1].first &&
        (j < 2 || vertex_fan[j - 2].first != vertex_fan[j].first))  // count each vertex once
      ++s.nonmanifold_vertices;

  std::size_t used_vertices = 0, interior = 0, interior_valence6 = 0;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    if (!referenced[v]) continue;
    ++used_vertices;
    if (components.find(v) == v) ++s.components;
    if (!on_boundary[v]) {
      ++interior;
      interior_valence6 += valence[v] == 6 ? 1 : 0;
    }
  }
  s.valence6_fraction = interior > 0 ? static_cast<double>(interior_valence6) / interior : kNaN;
  s.euler_characteristic = static_cast<int>(used_vertices) - static_cast<int>(edges) + static_cast<int>(faces.size());
  s.watertight = !faces.empty() && s.boundary_edges == 0 && s.nonmanifold_edges == 0 && s.nonmanifold_vertices == 0;
  // Each closed component has chi_i = 2 - 2 g_i, so the total genus is (2 C - chi) / 2.
  s.genus = s.watertight ? (2.0 * static_cast<double>(s.components) - s.euler_characteristic) / 2.0 : kNaN;
  return s;
}

}  // namespace dtsl
