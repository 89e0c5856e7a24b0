// Small meshes with known geometry and topology for the metric and normal tests.
#pragma once

#include <cmath>
#include <map>
#include <utility>

#include "framework/core/types.hpp"

namespace dtsl::test {

inline TriangleMesh tetrahedron() {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.faces = {{{0, 2, 1}}, {{0, 1, 3}}, {{0, 3, 2}}, {{1, 2, 3}}};  // outward
  return m;
}

/// Axis-aligned box as 12 outward triangles.
inline TriangleMesh cube(const Vec3& lo = Vec3(0, 0, 0), const Vec3& hi = Vec3(1, 1, 1)) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.faces.push_back({{q[0], q[1], q[2]}});
    m.faces.push_back({{q[0], q[2], q[3]}});
  }
  return m;
}

/// Icosahedron subdivided `levels` times, vertices on the sphere of `radius` (outward faces).
inline TriangleMesh icosphere(int levels, double radius = 1.0, const Vec3& center = Vec3::Zero()) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3& p : v) p.normalize();
  std::vector<Face> f = {{{0, 11, 5}}, {{0, 5, 1}},  {{0, 1, 7}},   {{0, 7, 10}}, {{0, 10, 11}},
                         {{1, 5, 9}},  {{5, 11, 4}}, {{11, 10, 2}}, {{10, 7, 6}}, {{7, 1, 8}},
                         {{3, 9, 4}},  {{3, 4, 2}},  {{3, 2, 6}},   {{3, 6, 8}},  {{3, 8, 9}},
                         {{4, 9, 5}},  {{2, 4, 11}}, {{6, 2, 10}},  {{8, 6, 7}},  {{9, 8, 1}}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    const auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return mid[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<Face> g;
    for (const Face& t3 : f) {
      const int a = midpoint(t3[0], t3[1]), b = midpoint(t3[1], t3[2]), c = midpoint(t3[2], t3[0]);
      g.push_back({{t3[0], a, c}});
      g.push_back({{t3[1], b, a}});
      g.push_back({{t3[2], c, b}});
      g.push_back({{a, b, c}});
    }
    f = std::move(g);
  }
  TriangleMesh m;
  for (const Vec3& p : v) m.vertices.push_back(center + radius * p);
  m.faces = std::move(f);
  return m;
}

/// Torus around the z axis (major radius R, minor r) as an nu x nv grid split into triangles; outward.
inline TriangleMesh torus(double R, double r, int nu, int nv) {
  TriangleMesh m;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * pi * i / nu, w = 2 * pi * j / nv;
      m.vertices.emplace_back((R + r * std::cos(w)) * std::cos(u), (R + r * std::cos(w)) * std::sin(u), r * std::sin(w));
    }
  const auto id = [&](int i, int j) { return ((i + nu) % nu) * nv + (j + nv) % nv; };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.faces.push_back({{id(i, j), id(i + 1, j), id(i + 1, j + 1)}});
      m.faces.push_back({{id(i, j), id(i + 1, j + 1), id(i, j + 1)}});
    }
  return m;
}

/// The rectangle [x0,x1] x [y0,y1] at height z, as two triangles facing +z.
inline TriangleMesh rectangle(double x0, double x1, double y0, double y1, double z = 0.0) {
  TriangleMesh m;
  m.vertices = {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}};
  m.faces = {{{0, 1, 2}}, {{0, 2, 3}}};
  return m;
}

/// Analytic outward normal of the torus above at a point near its surface.
inline Vec3 torus_normal(double R, const Vec3& p) {
  const Vec3 ring = R * Vec3(p.x(), p.y(), 0.0).normalized();
  return (p - ring).normalized();
}

inline void append(TriangleMesh& to, const TriangleMesh& from) {
  const int offset = static_cast<int>(to.vertices.size());
  to.vertices.insert(to.vertices.end(), from.vertices.begin(), from.vertices.end());
  for (Face f : from.faces) {
    for (int& i : f) i += offset;
    to.faces.push_back(f);
  }
}

}  // namespace dtsl::test
