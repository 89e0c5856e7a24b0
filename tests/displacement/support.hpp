// Shared helpers for the displacement tests: a marching-triangulation base mesh of an analytic
// implicit, area-uniform-ish directions (Fibonacci sphere) and dihedral angles per edge.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "algorithms/polygonize/marching_triangulation.hpp"
#include "framework/core/implicit.hpp"
#include "framework/core/mesh_adjacency.hpp"

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
  const MeshEdges edges = mesh_edges(m);
  const auto normal = [&m](int f) {
    const Face& t = m.faces[f];
    return Vec3((m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).normalized());
  };
  std::map<std::pair<int, int>, double> out;
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (edges.face_count(e) == 2) {
      const double c = normal(edges.faces[edges.first_face[e]]).dot(normal(edges.faces[edges.first_face[e] + 1]));
      out[{edges.ends[e][0], edges.ends[e][1]}] = std::acos(std::clamp(c, -1.0, 1.0));
    }
  return out;
}

}  // namespace dtsl::test
