// Shared helpers for the displacement tests: a marching-triangulation base mesh of an analytic
// implicit, area-uniform-ish directions (Fibonacci sphere) and dihedral angles per edge.
#pragma once

#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "algorithms/polygonize/marching_triangulation.hpp"
#include "framework/core/implicit.hpp"

namespace dtsl::test {

inline TriangleMesh base_mesh(const ImplicitFunction& f, const Vec3& seed, double step) {
  MarchingTriangulationOptions o;
  o.step = step;
  return marching_triangulation(f, {seed}, o).mesh;
}

/// n nearly uniform unit directions.
inline std::vector<Vec3> fibonacci_directions(int n) {
  std::vector<Vec3> out;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1 - z * z), phi = golden * i;
    out.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
  }
  return out;
}

/// Angle (radians) between the normals of the two faces of every interior edge, keyed by the edge.
inline std::map<std::pair<int, int>, double> dihedral_angles(const TriangleMesh& m) {
  std::map<std::pair<int, int>, std::vector<Vec3>> normals;
  for (const Face& f : m.faces) {
    const Vec3 n = (m.vertices[f[1]] - m.vertices[f[0]]).cross(m.vertices[f[2]] - m.vertices[f[0]]).normalized();
    for (int k = 0; k < 3; ++k) {
      const int a = f[k], b = f[(k + 1) % 3];
      normals[{std::min(a, b), std::max(a, b)}].push_back(n);
    }
  }
  std::map<std::pair<int, int>, double> out;
  for (const auto& e : normals)
    if (e.second.size() == 2) out[e.first] = std::acos(std::clamp(e.second[0].dot(e.second[1]), -1.0, 1.0));
  return out;
}

}  // namespace dtsl::test
