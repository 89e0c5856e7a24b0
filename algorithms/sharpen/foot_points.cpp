#include "algorithms/sharpen/foot_points.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_map>
#include <utility>

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

// The cells of a uniform grid that some boxes overlap, and which boxes: overlaps() is exact, the cells only
// rule out most queries quickly.
class BoxCells {
 public:
  explicit BoxCells(std::vector<BoundingBox> boxes) : boxes_(std::move(boxes)) {
    double extent = 0.0;
    for (const BoundingBox& b : boxes_) box_.extend(b.min), box_.extend(b.max), extent += (b.max - b.min).maxCoeff();
    if (boxes_.empty()) {
      marked_.assign(1, false);
      return;
    }
    // Cells about a box wide, no narrower than a millionth of the whole, and no more than kMaxCells.
    const Vec3 size = box_.max - box_.min;
    cell_ = std::max({extent / double(boxes_.size()), 1e-6 * size.norm(), 1e-300});
    const auto cells = [&](double c) { return (1.0 + size.x() / c) * (1.0 + size.y() / c) * (1.0 + size.z() / c); };
    while (cells(cell_) > kMaxCells) cell_ *= 1.25;
    for (int a = 0; a < 3; ++a) dims_[a] = 1 + long(size[a] / cell_);
    marked_.assign(std::size_t(dims_[0] * dims_[1] * dims_[2]), false);
    for (std::size_t i = 0; i < boxes_.size(); ++i)
      visit(boxes_[i], [&](std::size_t c) {
        marked_[c] = true;
        in_cell_[c].push_back(int(i));
        return false;
      });
  }
  bool overlaps(const BoundingBox& b) const {
    if (!box_.valid() || (b.max.array() < box_.min.array()).any() || (b.min.array() > box_.max.array()).any())
      return false;
    return visit(b, [&](std::size_t c) {
      if (!marked_[c]) return false;
      for (const int i : in_cell_.at(c)) {
        const BoundingBox& o = boxes_[std::size_t(i)];
        if ((b.max.array() >= o.min.array()).all() && (b.min.array() <= o.max.array()).all()) return true;
      }
      return false;
    });
  }
  /// overlaps(b), or b spans more than `max_cells` cells (true without visiting them).
  bool may_overlap(const BoundingBox& b, double max_cells) const {
    const Vec3 span = (b.max - b.min) / cell_ + Vec3::Ones();
    return span.prod() > max_cells || overlaps(b);
  }

 private:
  static constexpr double kMaxCells = 64.0 * 1024 * 1024;
  long index(int axis, double x) const {
    return long(std::clamp((x - box_.min[axis]) / cell_, 0.0, double(dims_[axis] - 1)));
  }
  // Calls f on the cells b overlaps until it returns true; whether it did.
  template <class F>
  bool visit(const BoundingBox& b, F f) const {
    for (long x = index(0, b.min.x()); x <= index(0, b.max.x()); ++x)
      for (long y = index(1, b.min.y()); y <= index(1, b.max.y()); ++y)
        for (long z = index(2, b.min.z()); z <= index(2, b.max.z()); ++z)
          if (f(std::size_t((x * dims_[1] + y) * dims_[2] + z))) return true;
    return false;
  }
  std::vector<BoundingBox> boxes_;
  BoundingBox box_;
  double cell_ = 1.0;
  long dims_[3] = {1, 1, 1};
  std::vector<bool> marked_;
  std::unordered_map<std::size_t, std::vector<int>> in_cell_;  // the boxes overlapping each marked cell
};

// The box of b grown by `grow`, and by a few rounding errors of its coordinates more (a face at exactly
// that distance must not be left out by rounding).
BoundingBox grown(BoundingBox b, double grow) {
  const double pad = grow * (1.0 + 1e-12) + 1e-12 * std::max(b.min.cwiseAbs().maxCoeff(), b.max.cwiseAbs().maxCoeff());
  b.min.array() -= pad;
  b.max.array() += pad;
  return b;
}

BoundingBox face_box(const TriangleMesh& mesh, int face, double grow) {
  BoundingBox b;
  for (const int v : mesh.faces[std::size_t(face)]) b.extend(mesh.vertices[std::size_t(v)]);
  return grown(b, grow);
}

// The faces of `mesh` listed, as a mesh of their own for MeshDistance (nothing if none has an area: it
// leaves zero-area faces out and rejects a mesh of only those).
std::optional<TriangleMesh> face_subset(const TriangleMesh& mesh, const std::vector<int>& faces) {
  TriangleMesh part;
  part.vertices = mesh.vertices;
  bool area = false;
  for (const int f : faces) {
    const Face& t = mesh.faces[std::size_t(f)];
    part.faces.push_back(t);
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    area = area || (b - a).cross(c - a).squaredNorm() > 0.0;
  }
  if (!area) return std::nullopt;
  return part;
}

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
  for (std::size_t k = 0; k < points.size(); ++k)
    feet[k] = foot_at(mesh, hits[k].point, hits[k].distance, hits[k].face, snap);
  return feet;
}

std::vector<FootPoint> update_foot_points(const TriangleMesh& before, const TriangleMesh& after,
                                          const std::vector<std::vector<int>>& vertex_faces,
                                          const std::vector<FootPoint>& feet, const std::vector<Vec3>& points,
                                          double snap) {
  if (after.faces != before.faces || after.vertices.size() != before.vertices.size() ||
      vertex_faces.size() != after.vertices.size() || feet.size() != points.size())
    throw AlgorithmError("foot point update: the meshes must share their faces, and feet match the points");
  for (const FootPoint& f : feet)
    if (f.face < 0 || std::size_t(f.face) >= after.faces.size())
      throw AlgorithmError("foot point update: a foot's face " + std::to_string(f.face) + " is not a face of the mesh");
  std::vector<char> changed(after.faces.size(), 0);
  std::vector<int> changed_faces;
  for (std::size_t v = 0; v < after.vertices.size(); ++v)
    if (after.vertices[v] != before.vertices[v])
      for (const int f : vertex_faces[v])
        if (!changed[std::size_t(f)]) changed[std::size_t(f)] = 1, changed_faces.push_back(f);
  if (changed_faces.empty()) return feet;
  std::sort(changed_faces.begin(), changed_faces.end());

  // A point whose foot lies on an unchanged face keeps it unless a moved face came closer, which needs the
  // moved face's box within the foot's distance of the point. Each point is tested with its own distance:
  // one bound for all (the largest, an outlier's) would send most points near a moved face to the search.
  std::vector<BoundingBox> moved_boxes;
  for (const int f : changed_faces) moved_boxes.push_back(face_box(after, f, 0.0));
  const BoxCells moved_cells(std::move(moved_boxes));
  constexpr double kMaxCellsTested = 64.0;  // a point farther than that from the mesh is searched anyway
  std::vector<std::size_t> kept, lost;
  for (std::size_t k = 0; k < feet.size(); ++k) {
    if (changed[std::size_t(feet[k].face)]) {
      lost.push_back(k);
    } else {
      const BoundingBox reach = grown(BoundingBox{points[k], points[k]}, feet[k].distance);
      if (moved_cells.may_overlap(reach, kMaxCellsTested)) kept.push_back(k);
    }
  }
  std::vector<FootPoint> out = feet;
  const std::optional<TriangleMesh> moved = face_subset(after, changed_faces);
  if (!moved) return foot_points(after, points, snap);  // every moved face lost its area: search anew
  const MeshDistance moved_faces(*moved);
  const auto hits = moved_faces.closest_all(select(points, kept));
  for (std::size_t i = 0; i < kept.size(); ++i)
    if (hits[i].distance < feet[kept[i]].distance)
      out[kept[i]] = foot_at(after, hits[i].point, hits[i].distance, changed_faces[std::size_t(hits[i].face)], snap);
  if (lost.empty()) return out;
  // A point whose foot's face moved: its nearest moved face bounds the search; the unchanged faces
  // within that bound of some such point are searched as well.
  const std::vector<Vec3> lost_points = select(points, lost);
  const auto on_moved = moved_faces.closest_all(lost_points);
  std::vector<BoundingBox> lost_boxes;
  for (std::size_t i = 0; i < lost.size(); ++i)
    lost_boxes.push_back(grown(BoundingBox{lost_points[i], lost_points[i]}, on_moved[i].distance));
  const BoxCells near_lost(std::move(lost_boxes));
  std::vector<int> unchanged_near;
  for (std::size_t f = 0; f < after.faces.size(); ++f)
    if (!changed[f] && near_lost.overlaps(face_box(after, int(f), 0.0))) unchanged_near.push_back(int(f));
  const std::optional<TriangleMesh> around = face_subset(after, unchanged_near);
  std::vector<MeshDistance::Hit> on_unchanged;
  if (around) on_unchanged = MeshDistance(*around).closest_all(lost_points);
  for (std::size_t i = 0; i < lost.size(); ++i) {
    if (around && on_unchanged[i].distance < on_moved[i].distance)
      out[lost[i]] = foot_at(after, on_unchanged[i].point, on_unchanged[i].distance,
                             unchanged_near[std::size_t(on_unchanged[i].face)], snap);
    else
      out[lost[i]] = foot_at(after, on_moved[i].point, on_moved[i].distance,
                             changed_faces[std::size_t(on_moved[i].face)], snap);
  }
  return out;
}

double mean_distance(const std::vector<FootPoint>& feet) {
  double s = 0.0;
  for (const auto& f : feet) s += f.distance;
  return feet.empty() ? 0.0 : s / static_cast<double>(feet.size());
}

}  // namespace dtsl::sharpen
