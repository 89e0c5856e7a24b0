// Small mesh helpers shared by the shape sources and samplers (see internal.hpp).
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <utility>

#include <Eigen/Geometry>

#include "framework/datasets/internal.hpp"

namespace dtsl::dataset_detail {

std::vector<Vec3> area_weighted_vertex_normals(const TriangleMesh& mesh) {
  std::vector<Vec3> n(mesh.vertices.size(), Vec3::Zero());
  for (const Face& f : mesh.faces) {
    const Vec3 c = (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]);
    for (int k = 0; k < 3; ++k) n[f[k]] += c;
  }
  for (Vec3& v : n) {
    const double len = v.norm();
    v = len > 0.0 ? Vec3(v / len) : Vec3::Zero();
  }
  return n;
}

std::vector<Vec3> angle_weighted_vertex_normals(const TriangleMesh& mesh) {
  std::vector<Vec3> n(mesh.vertices.size(), Vec3::Zero());
  for (const Face& f : mesh.faces) {
    const Vec3 c = (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]);
    const double len = c.norm();
    if (!(len > 0.0)) continue;
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = mesh.vertices[f[(k + 1) % 3]] - mesh.vertices[f[k]];
      const Vec3 b = mesh.vertices[f[(k + 2) % 3]] - mesh.vertices[f[k]];
      const double angle = std::atan2(a.cross(b).norm(), a.dot(b));
      n[f[k]] += angle * c / len;
    }
  }
  for (Vec3& v : n) {
    const double len = v.norm();
    v = len > 0.0 ? Vec3(v / len) : Vec3::Zero();
  }
  return n;
}

double signed_volume(const TriangleMesh& mesh) {
  // Relative to the box centre rather than the origin: far from the origin the per-face terms are
  // large and cancel, losing digits.
  const Vec3 o = bounding_box(mesh.vertices).center();
  double v = 0.0;
  for (const Face& f : mesh.faces)
    v += (mesh.vertices[f[0]] - o).dot((mesh.vertices[f[1]] - o).cross(mesh.vertices[f[2]] - o));
  return v / 6.0;
}

bool orient_outward(TriangleMesh& mesh) {
  if (mesh.faces.empty() || signed_volume(mesh) >= 0.0) return false;
  for (Face& f : mesh.faces) std::swap(f[1], f[2]);
  for (Vec3& n : mesh.normals) n = -n;
  return true;
}

std::vector<bool> referenced_vertices(const TriangleMesh& mesh) {
  std::vector<bool> used(mesh.vertices.size(), false);
  for (const Face& f : mesh.faces)
    for (int k = 0; k < 3; ++k) used[f[k]] = true;
  return used;
}

TriangleMesh icosphere(const Vec3& centre, double radius, int subdivisions) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3& p : v) p.normalize();
  std::vector<Face> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                             {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                             {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                             {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int s = 0; s < subdivisions; ++s) {
    // Each edge's midpoint is created once and shared by both faces, so the result stays closed.
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      const int i = static_cast<int>(v.size()) - 1;
      midpoint.emplace(key, i);
      return i;
    };
    std::vector<Face> next;
    next.reserve(4 * faces.size());
    for (const Face& f : faces) {
      const int a = mid(f[0], f[1]), b = mid(f[1], f[2]), c = mid(f[2], f[0]);
      next.push_back({f[0], a, c});
      next.push_back({f[1], b, a});
      next.push_back({f[2], c, b});
      next.push_back({a, b, c});
    }
    faces.swap(next);
  }
  TriangleMesh mesh;
  mesh.faces = std::move(faces);
  mesh.normals = v;  // the unit directions are the exact normals of the sphere
  mesh.vertices.reserve(v.size());
  for (const Vec3& d : v) mesh.vertices.push_back(centre + radius * d);
  return mesh;
}

void append(TriangleMesh& mesh, const TriangleMesh& part) {
  const int offset = static_cast<int>(mesh.vertices.size());
  mesh.vertices.insert(mesh.vertices.end(), part.vertices.begin(), part.vertices.end());
  mesh.normals.insert(mesh.normals.end(), part.normals.begin(), part.normals.end());
  for (const Face& f : part.faces) mesh.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
}

Vec3 to_vec3(const std::vector<double>& v) { return Vec3(v.at(0), v.at(1), v.at(2)); }

std::string format_number(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

}  // namespace dtsl::dataset_detail
