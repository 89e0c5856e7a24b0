// Helpers shared by the polygonizer tests: points on an implicit surface, setting an option by name,
// two-sided Hausdorff distance to the true surface, and a brute-force (grid-accelerated)
// self-intersection test.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "algorithms/polygonize/newton_projection.hpp"
#include "framework/config/options.hpp"
#include "framework/core/sampling.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/polygonize/implicits.hpp"

namespace dtsl::test {

/// Up to `count` points on f = 0: random points in `box` projected by Newton (converged, inside box).
inline std::vector<Vec3> surface_points(const ImplicitFunction& f, const BoundingBox& box, std::size_t count,
                                        std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> out;
  for (std::size_t tries = 0; out.size() < count && tries < 50 * count; ++tries) {
    const Vec3 x = box.min + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(box.extent());
    const NewtonProjection r = newton_project(f, x);
    if (r.converged() && (r.point.array() >= box.min.array()).all() && (r.point.array() <= box.max.array()).all())
      out.push_back(r.point);
  }
  return out;
}

/// Sets option `name` of `o` through its visitor (numbers into int or double fields, text into string
/// fields, "true"/"false" into bool fields); throws if no field of a matching type has that name.
class OptionSetter final : public FieldVisitor {
 public:
  OptionSetter(std::string name, std::string text) : name_(std::move(name)), text_(std::move(text)) {}
  void field(const char* n, bool& v, const char*) override {
    if (name_ == n && (text_ == "true" || text_ == "false")) v = text_ == "true", found = true;
  }
  void field(const char* n, int& v, const char*) override {
    if (name_ == n && number()) v = std::stoi(text_), found = true;
  }
  void field(const char* n, double& v, const char*) override {
    if (name_ == n && number()) v = std::stod(text_), found = true;
  }
  void field(const char* n, std::string& v, const char*) override {
    if (name_ == n) v = text_, found = true;
  }
  void field(const char*, std::vector<double>&, const char*) override {}
  bool found = false;

 private:
  bool number() const {
    char* end = nullptr;
    std::strtod(text_.c_str(), &end);
    return end && *end == '\0' && !text_.empty();
  }
  std::string name_, text_;
};

inline void set_option(Options& o, const std::string& name, const std::string& text) {
  OptionSetter setter(name, text);
  o.visit(setter);
  if (!setter.found) throw std::runtime_error("no option " + name + " accepting '" + text + "'");
}
inline void set_option(Options& o, const std::string& name, double value) {
  std::ostringstream s;
  s.precision(17);
  s << value;
  set_option(o, name, s.str());
}

struct Hausdorff {
  double to_surface = 0.0;    ///< max distance of mesh vertices and area samples to the true surface
  double from_surface = 0.0;  ///< max distance of true surface points to the mesh
  double value() const { return std::max(to_surface, from_surface); }
};

inline Hausdorff hausdorff(const TriangleMesh& mesh, const AnalyticImplicit& f,
                           const std::vector<Vec3>& truth_samples, std::size_t area_samples = 20000) {
  Hausdorff h;
  for (const Vec3& v : mesh.vertices) h.to_surface = std::max(h.to_surface, f.distance(v));
  std::mt19937_64 rng(7);
  for (const SurfaceSample& s : sample_surface(mesh, area_samples, rng))
    h.to_surface = std::max(h.to_surface, f.distance(s.point));
  const MeshDistance md(mesh);
  for (const Vec3& p : truth_samples) h.from_surface = std::max(h.from_surface, md.closest(p).distance);
  return h;
}

namespace detail {

/// Segment [p, q] crosses the interior of triangle (a, b, c) away from its ends and the triangle's
/// boundary (Moller-Trumbore with strict margins: touching at a shared vertex is not a crossing).
inline bool segment_crosses(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const double eps = 1e-9;
  const Vec3 d = q - p, e1 = b - a, e2 = c - a;
  const Vec3 s = d.cross(e2);
  const double det = e1.dot(s);
  if (std::abs(det) < 1e-14 * e1.norm() * e2.norm() * d.norm()) return false;  // parallel / coplanar
  const double inv = 1.0 / det;
  const Vec3 t0 = p - a;
  const double u = t0.dot(s) * inv;
  if (u <= eps || u >= 1 - eps) return false;
  const Vec3 qv = t0.cross(e1);
  const double v = d.dot(qv) * inv;
  if (v <= eps || u + v >= 1 - eps) return false;
  const double t = e2.dot(qv) * inv;
  return t > eps && t < 1 - eps;
}

}  // namespace detail

/// Number of pairs of triangles that cross each other: an edge of one pierces the interior of the
/// other. Pairs sharing an edge are not tested, pairs sharing a vertex only through the edges away
/// from it; coplanar overlaps are not detected (none of the tested surfaces has flat parts).
inline std::size_t self_intersections(const TriangleMesh& mesh, std::vector<std::pair<int, int>>* pairs = nullptr) {
  double cell = 0.0;
  for (const Face& t : mesh.faces)
    for (int k = 0; k < 3; ++k)
      cell = std::max(cell, (mesh.vertices[t[k]] - mesh.vertices[t[(k + 1) % 3]]).norm());
  cell = std::max(cell, 1e-9);
  std::unordered_map<long long, std::vector<int>> grid;
  const auto key = [&](long long i, long long j, long long k) { return (i * 73856093LL) ^ (j * 19349663LL) ^ (k * 83492791LL); };
  const auto cells_of = [&](const Face& t, auto&& visit) {
    Eigen::Vector3d lo = mesh.vertices[t[0]], hi = lo;
    for (int v : t) {
      lo = lo.cwiseMin(mesh.vertices[v]);
      hi = hi.cwiseMax(mesh.vertices[v]);
    }
    for (long long i = std::floor(lo.x() / cell); i <= std::floor(hi.x() / cell); ++i)
      for (long long j = std::floor(lo.y() / cell); j <= std::floor(hi.y() / cell); ++j)
        for (long long k = std::floor(lo.z() / cell); k <= std::floor(hi.z() / cell); ++k) visit(key(i, j, k));
  };
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    cells_of(mesh.faces[f], [&](long long c) { grid[c].push_back(static_cast<int>(f)); });
  std::size_t count = 0;
  std::vector<int> seen(mesh.faces.size(), -1);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& t1 = mesh.faces[f];
    cells_of(t1, [&](long long c) {
      for (int g : grid[c]) {
        if (g <= static_cast<int>(f) || seen[g] == static_cast<int>(f)) continue;
        seen[g] = static_cast<int>(f);
        const Face& t2 = mesh.faces[g];
        int shared = 0;
        for (int a : t1)
          for (int b : t2) shared += a == b;
        if (shared >= 2) continue;
        // An edge through a vertex of the other triangle meets that triangle's plane only there (or
        // lies in it): testing it would only measure rounding. With one shared vertex, a crossing
        // shows as the opposite edge of one triangle piercing the other.
        const auto pierces = [&](const Face& a, const Face& b) {
          for (int k = 0; k < 3; ++k) {
            const int u = a[k], w = a[(k + 1) % 3];
            if (u == b[0] || u == b[1] || u == b[2] || w == b[0] || w == b[1] || w == b[2]) continue;
            if (detail::segment_crosses(mesh.vertices[u], mesh.vertices[w], mesh.vertices[b[0]], mesh.vertices[b[1]],
                                        mesh.vertices[b[2]]))
              return true;
          }
          return false;
        };
        const bool hit = pierces(t1, t2) || pierces(t2, t1);
        count += hit;
        if (hit && pairs) pairs->emplace_back(static_cast<int>(f), g);
      }
    });
  }
  return count;
}

/// Total area of the mesh.
inline double mesh_area(const TriangleMesh& mesh) {
  double a = 0.0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) a += face_area(mesh, static_cast<int>(f));
  return a;
}

}  // namespace dtsl::test
