#include "algorithms/sharpen/bilateral_target.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_set>
#include <vector>

namespace dtsl::sharpen {

Vec3 bilateral_target(const TriangleMesh& mesh, const MeshAdjacency& adj, int v, double sigma_c, double sigma_s,
                      double radius) {
  const Vec3& x = mesh.vertices[v];
  const double r2 = radius * radius;
  // Breadth-first over vertices within the radius; their faces form the candidate set N(v).
  std::vector<int> queue{v};
  std::unordered_set<int> seen_v{v}, seen_f;
  Vec3 sum = Vec3::Zero();
  double wsum = 0.0;
  for (std::size_t i = 0; i < queue.size(); ++i) {
    const int w = queue[i];
    for (const int f : adj.vertex_faces[w]) {
      if (!seen_f.insert(f).second) continue;
      const Face& t = mesh.faces[f];
      const Vec3& a = mesh.vertices[t[0]];
      const Vec3& b = mesh.vertices[t[1]];
      const Vec3& c = mesh.vertices[t[2]];
      const Vec3 cr = (b - a).cross(c - a);
      const double twice_area = cr.norm();
      if (!(twice_area > 0.0)) continue;  // a degenerate triangle has no plane
      const Vec3 centre = (a + b + c) / 3.0;
      const double dc2 = (x - centre).squaredNorm();
      if (dc2 > r2) continue;
      const Vec3 n = cr / twice_area;
      const double h = (x - centre).dot(n);  // signed distance of v to the plane: |v - v*_j|
      const Vec3 proj = x - h * n;           // v*_j
      const double wgt = std::exp(-dc2 / (2.0 * sigma_c * sigma_c)) * std::exp(-h * h / (2.0 * sigma_s * sigma_s)) *
                         0.5 * twice_area;
      sum += wgt * proj;
      wsum += wgt;
    }
    for (const int u : adj.vertex_neighbours[w])
      if ((mesh.vertices[u] - x).squaredNorm() <= r2 && seen_v.insert(u).second) queue.push_back(u);
  }
  return wsum > 0.0 ? Vec3(sum / wsum) : x;
}

}  // namespace dtsl::sharpen
