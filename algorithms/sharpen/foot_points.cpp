#include "algorithms/sharpen/foot_points.hpp"

#include <algorithm>
#include <cmath>

#include "framework/core/error.hpp"
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

namespace {

// The foot point of a closest-point hit on face `face` of `mesh`.
FootPoint foot_at(const TriangleMesh& mesh, const Vec3& q, double distance, int face, double snap) {
  const Face& t = mesh.faces[face];
  const std::array<double, 3> l = barycentric(q, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
  FootPoint f;
  f.q = q;
  f.distance = distance;
  f.face = face;
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
  return f;
}

// The cells of a uniform grid that the boxes of some faces, grown by `reach`, overlap: a point in no
// marked cell is farther than `reach` from every one of those faces.
class MovedFaceCells {
 public:
  MovedFaceCells(const TriangleMesh& mesh, const std::vector<int>& faces, double reach) {
    double extent = 0.0;
    for (const int f : faces) {
      const Face& t = mesh.faces[std::size_t(f)];
      BoundingBox b;
      for (const int v : t) b.extend(mesh.vertices[std::size_t(v)]), box_.extend(mesh.vertices[std::size_t(v)]);
      extent += (b.max - b.min).maxCoeff();
    }
    box_.min.array() -= reach;
    box_.max.array() += reach;
    // Cells about a face wide, and no more than kMaxCells of them.
    cell_ = std::max(extent / double(faces.size()) + 2.0 * reach, 1e-12);
    const double volume = (box_.max - box_.min).prod();
    cell_ = std::max(cell_, std::cbrt(volume / kMaxCells));
    for (int a = 0; a < 3; ++a) dims_[a] = 1 + long((box_.max[a] - box_.min[a]) / cell_);
    marked_.assign(std::size_t(dims_[0] * dims_[1] * dims_[2]), false);
    for (const int f : faces) {
      const Face& t = mesh.faces[std::size_t(f)];
      BoundingBox b;
      for (const int v : t) b.extend(mesh.vertices[std::size_t(v)]);
      const std::array<long, 3> lo = index(b.min.array() - reach), hi = index(b.max.array() + reach);
      for (long x = lo[0]; x <= hi[0]; ++x)
        for (long y = lo[1]; y <= hi[1]; ++y)
          for (long z = lo[2]; z <= hi[2]; ++z) marked_[std::size_t((x * dims_[1] + y) * dims_[2] + z)] = true;
    }
  }
  bool contains(const Vec3& p) const {
    if ((p.array() < box_.min.array()).any() || (p.array() > box_.max.array()).any()) return false;
    const std::array<long, 3> i = index(p.array());
    return marked_[std::size_t((i[0] * dims_[1] + i[1]) * dims_[2] + i[2])];
  }

 private:
  static constexpr double kMaxCells = 64.0 * 1024 * 1024;
  std::array<long, 3> index(const Eigen::Array3d& p) const {
    std::array<long, 3> i{};
    for (int a = 0; a < 3; ++a) i[a] = std::clamp(long((p[a] - box_.min[a]) / cell_), 0L, dims_[a] - 1);
    return i;
  }
  BoundingBox box_;
  double cell_ = 1.0;
  long dims_[3] = {1, 1, 1};
  std::vector<bool> marked_;
};

std::vector<Vec3> select(const std::vector<Vec3>& points, const std::vector<std::size_t>& which) {
  std::vector<Vec3> out;
  out.reserve(which.size());
  for (const std::size_t k : which) out.push_back(points[k]);
  return out;
}

}  // namespace

std::vector<FootPoint> foot_points(const TriangleMesh& mesh, const std::vector<Vec3>& points, double snap) {
  const MeshDistance tree(mesh);
  const std::vector<MeshDistance::Hit> hits = tree.closest_all(points);
  std::vector<FootPoint> feet(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) feet[k] = foot_at(mesh, hits[k].point, hits[k].distance, hits[k].face, snap);
  return feet;
}

std::vector<FootPoint> update_foot_points(const TriangleMesh& before, const TriangleMesh& after,
                                          const std::vector<std::vector<int>>& vertex_faces,
                                          const std::vector<FootPoint>& feet, const std::vector<Vec3>& points,
                                          double snap) {
  if (after.faces != before.faces || after.vertices.size() != before.vertices.size() ||
      vertex_faces.size() != after.vertices.size() || feet.size() != points.size())
    throw AlgorithmError("foot point update: the meshes must share their faces, and feet match the points");
  std::vector<char> changed(after.faces.size(), 0);
  std::vector<int> changed_faces;
  for (std::size_t v = 0; v < after.vertices.size(); ++v)
    if (after.vertices[v] != before.vertices[v])
      for (const int f : vertex_faces[v])
        if (!changed[std::size_t(f)]) changed[std::size_t(f)] = 1, changed_faces.push_back(f);
  if (changed_faces.empty()) return feet;
  std::sort(changed_faces.begin(), changed_faces.end());

  // A point whose foot lies on an unchanged face keeps it unless a moved face came closer, which needs the
  // point within its foot's distance (at most `reach`) of that face's box; the others are searched on the
  // whole mesh again.
  double reach = 0.0;
  for (const FootPoint& f : feet) reach = std::max(reach, f.distance);
  const MovedFaceCells near(after, changed_faces, reach);
  std::vector<std::size_t> kept, lost;
  for (std::size_t k = 0; k < feet.size(); ++k) {
    if (changed[std::size_t(feet[k].face)]) lost.push_back(k);
    else if (near.contains(points[k])) kept.push_back(k);
  }
  std::vector<FootPoint> out = feet;
  TriangleMesh moved;
  moved.vertices = after.vertices;
  for (const int f : changed_faces) moved.faces.push_back(after.faces[std::size_t(f)]);
  if (std::any_of(moved.faces.begin(), moved.faces.end(), [&](const Face& t) {  // MeshDistance skips zero-area faces
        return (after.vertices[t[1]] - after.vertices[t[0]]).cross(after.vertices[t[2]] - after.vertices[t[0]]).squaredNorm() > 0.0;
      })) {
    const std::vector<MeshDistance::Hit> hits = MeshDistance(moved).closest_all(select(points, kept));
    for (std::size_t i = 0; i < kept.size(); ++i)
      if (hits[i].distance < feet[kept[i]].distance)
        out[kept[i]] = foot_at(after, hits[i].point, hits[i].distance, changed_faces[std::size_t(hits[i].face)], snap);
  }
  if (!lost.empty()) {
    const std::vector<MeshDistance::Hit> hits = MeshDistance(after).closest_all(select(points, lost));
    for (std::size_t i = 0; i < lost.size(); ++i) out[lost[i]] = foot_at(after, hits[i].point, hits[i].distance, hits[i].face, snap);
  }
  return out;
}

double mean_distance(const std::vector<FootPoint>& feet) {
  double s = 0.0;
  for (const auto& f : feet) s += f.distance;
  return feet.empty() ? 0.0 : s / static_cast<double>(feet.size());
}

}  // namespace dtsl::sharpen
