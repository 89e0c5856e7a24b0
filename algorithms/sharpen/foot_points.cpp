#include "algorithms/sharpen/foot_points.hpp"

#include <algorithm>

#include "framework/metrics/metrics.hpp"

namespace dtsl::sharpen {

std::array<double, 3> barycentric(const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e0 = b - a, e1 = c - a, d = q - a;
  const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
  const double d20 = d.dot(e0), d21 = d.dot(e1);
  const double den = d00 * d11 - d01 * d01;
  if (!(den > 0.0)) return {1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0};  // degenerate: MeshDistance skips these
  const double v = (d11 * d20 - d01 * d21) / den;
  const double w = (d00 * d21 - d01 * d20) / den;
  return {1.0 - v - w, v, w};
}

std::vector<FootPoint> foot_points(const TriangleMesh& mesh, const std::vector<Vec3>& points, double snap) {
  const MeshDistance tree(mesh);
  const std::vector<MeshDistance::Hit> hits = tree.closest_all(points);
  std::vector<FootPoint> feet(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto& h = hits[k];
    const Face& t = mesh.faces[h.face];
    std::array<double, 3> l = barycentric(h.point, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
    FootPoint& f = feet[k];
    f.q = h.point;
    f.distance = h.distance;
    f.face = h.face;
    f.count = 0;
    double sum = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double lc = std::clamp(l[c], 0.0, 1.0);
      if (lc > snap) {  // Fig. 2: drop the vertices the foot point does not depend on
        f.vertices[f.count] = t[c];
        f.lambda[f.count] = lc;
        sum += lc;
        ++f.count;
      }
    }
    if (f.count == 0) {  // cannot happen for a hit on a non-degenerate face; be safe
      f.count = 1;
      f.vertices[0] = t[0];
      f.lambda[0] = sum = 1.0;
    }
    for (int c = 0; c < f.count; ++c) f.lambda[c] /= sum;
  }
  return feet;
}

double mean_distance(const std::vector<FootPoint>& feet) {
  double s = 0.0;
  for (const auto& f : feet) s += f.distance;
  return feet.empty() ? 0.0 : s / static_cast<double>(feet.size());
}

}  // namespace dtsl::sharpen
