#include "algorithms/polygonize/seeding.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "framework/core/error.hpp"
#include "framework/core/mesh_adjacency.hpp"

namespace dtsl {

namespace {

bool inside(const BoundingBox& box, const Vec3& p) {
  return (p.array() >= box.min.array()).all() && (p.array() <= box.max.array()).all();
}

void collect(const ImplicitFunction& f, const std::vector<NewtonProjection>& projections, SeedCandidates& out) {
  const BoundingBox domain = f.domain();
  out.candidates += projections.size();
  for (const NewtonProjection& r : projections) {
    if (!r.converged()) {
      ++out.failures;
    } else if (!inside(domain, r.point)) {
      ++out.outside_domain;
    } else {
      out.points.push_back(r.point);
    }
  }
}

/// Whether most of `part` lies on the components already in `mesh` (vertices in `earlier`): more than
/// half of up to 64 of its vertices, spread over it, have a vertex of `mesh` within `reach`. Two
/// distinct components of a zero set cannot be that close over most of one of them.
bool remeshes_earlier(const TriangleMesh& part, const TriangleMesh& mesh, const SpatialHash& earlier, double reach) {
  if (mesh.vertices.empty() || part.vertices.empty()) return false;
  const std::size_t n = part.vertices.size(), stride = std::max<std::size_t>(1, n / 64);
  std::size_t samples = 0, on_earlier = 0;
  for (std::size_t v = 0; v < n; v += stride) {
    ++samples;
    const Vec3& p = part.vertices[v];
    bool near = false;
    earlier.for_each_near(p, reach, [&](int id) {
      near = near || (mesh.vertices[static_cast<std::size_t>(id)] - p).norm() <= reach;
    });
    on_earlier += near;
  }
  return 2 * on_earlier > samples;
}

}  // namespace

SeedCandidates foot_point_seeds(const ImplicitFunction& f, const std::vector<Vec3>& data,
                                const NewtonOptions& newton) {
  SeedCandidates out;
  collect(f, newton_project_all(f, data, newton), out);
  return out;
}

SeedCandidates grid_seeds(const ImplicitFunction& f, const BoundingBox& box, double spacing,
                          const NewtonOptions& newton) {
  if (!box.valid() || !(spacing > 0.0)) throw AlgorithmError("grid seeds: invalid box or spacing");
  Eigen::Vector3i n;
  for (int a = 0; a < 3; ++a) n[a] = std::max(2, static_cast<int>(std::ceil(box.extent()[a] / spacing)) + 1);
  const long total = static_cast<long>(n.x()) * n.y() * n.z();
  if (total > 200'000'000L) throw AlgorithmError("grid seeds: spacing " + std::to_string(spacing) + " is too fine");
  const auto at = [&](int i, int j, int k) {
    return Vec3(box.min.x() + i * spacing, box.min.y() + j * spacing, box.min.z() + k * spacing);
  };
  std::vector<double> values(static_cast<std::size_t>(total));
#pragma omp parallel for schedule(dynamic, 1)
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i)
        values[(static_cast<std::size_t>(k) * n.y() + j) * n.x() + i] = f.value(at(i, j, k));
  const auto value = [&](int i, int j, int k) { return values[(static_cast<std::size_t>(k) * n.y() + j) * n.x() + i]; };
  // A root estimate on every sign-changing grid edge, by linear interpolation; Newton does the rest.
  std::vector<Vec3> starts;
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        const double v0 = value(i, j, k);
        const int step[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        for (const auto& s : step) {
          const int i1 = i + s[0], j1 = j + s[1], k1 = k + s[2];
          if (i1 >= n.x() || j1 >= n.y() || k1 >= n.z()) continue;
          const double v1 = value(i1, j1, k1);
          if ((v0 < 0.0) == (v1 < 0.0)) continue;
          const double t = v0 / (v0 - v1);
          starts.push_back(at(i, j, k) + t * (at(i1, j1, k1) - at(i, j, k)));
        }
      }
  SeedCandidates out;
  collect(f, newton_project_all(f, starts, newton), out);
  return out;
}

double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Ericson, Real-Time Collision Detection §5.1.5: the closest point by the Voronoi region of p.
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.norm();
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + ab * (d1 / (d1 - d3)))).norm();
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + ac * (d2 / (d2 - d6)))).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).norm();
  const double denom = va + vb + vc;
  if (!(std::abs(denom) > 0.0)) return std::min({ap.norm(), bp.norm(), cp.norm()});  // degenerate triangle
  const double v = vb / denom, w = vc / denom;
  return (p - (a + ab * v + ac * w)).norm();
}

MeshProximity::MeshProximity(const TriangleMesh& mesh, double radius)
    : mesh_(mesh), radius_(radius), hash_(radius), vertex_faces_(vertex_faces(mesh, "mesh proximity")) {
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) hash_.insert(static_cast<int>(v), mesh.vertices[v]);
}

MeshProximity::Hit MeshProximity::closest(const Vec3& p) const {
  Hit best{std::numeric_limits<double>::infinity(), -1};
  const double r2 = radius_ * radius_;
  hash_.for_each_near(p, radius_, [&](int v) {
    if ((mesh_.vertices[static_cast<std::size_t>(v)] - p).squaredNorm() > r2) return;
    for (int f : vertex_faces_[static_cast<std::size_t>(v)]) {
      const Face& t = mesh_.faces[static_cast<std::size_t>(f)];
      const double d = point_triangle_distance(p, mesh_.vertices[static_cast<std::size_t>(t[0])],
                                               mesh_.vertices[static_cast<std::size_t>(t[1])],
                                               mesh_.vertices[static_cast<std::size_t>(t[2])]);
      if (d < best.distance) best = {d, f};
    }
  });
  return best;
}

void append_mesh(TriangleMesh& mesh, const TriangleMesh& part) {
  const int offset = static_cast<int>(mesh.vertices.size());
  const bool normals = (mesh.vertices.empty() || mesh.has_normals()) && part.has_normals();
  if (!normals) mesh.normals.clear();
  mesh.vertices.insert(mesh.vertices.end(), part.vertices.begin(), part.vertices.end());
  if (normals) mesh.normals.insert(mesh.normals.end(), part.normals.begin(), part.normals.end());
  for (const Face& t : part.faces) mesh.faces.push_back({{t[0] + offset, t[1] + offset, t[2] + offset}});
}

SeededMeshing mesh_from_seeds(const std::vector<Vec3>& seeds, double cover_distance, double proximity_radius,
                              double skip_radius, std::size_t max_components,
                              const std::function<ComponentMesh(const Vec3& seed)>& march) {
  SeededMeshing out;
  std::vector<Vec3> remaining = seeds;  // P, in input order: the first left is the next seed (step 4)
  std::vector<char> keep;
  SpatialHash earlier(proximity_radius);  // the vertices of the components kept so far
  while (!remaining.empty()) {
    const Vec3 seed = remaining.front();
    ComponentMesh part = march(seed);
    keep.assign(remaining.size(), 1);
    const long n = static_cast<long>(remaining.size());
    if (part.skipped || part.mesh.faces.empty()) {
      ++out.skipped_seeds;
      for (long i = 0; i < n; ++i)
        if ((remaining[static_cast<std::size_t>(i)] - seed).norm() <= skip_radius) keep[static_cast<std::size_t>(i)] = 0;
      keep[0] = 0;  // never retry the same seed
    } else {
      // Step 5: drop the seeds the new mesh covers; the seed itself lies on the component it started,
      // so it is never marched from again even if the mesh's triangles are a little off the surface there.
      const MeshProximity near(part.mesh, proximity_radius);
#pragma omp parallel for schedule(dynamic, 1024)
      for (long i = 0; i < n; ++i)
        if (near.closest(remaining[static_cast<std::size_t>(i)]).distance <= cover_distance) keep[static_cast<std::size_t>(i)] = 0;
      keep[0] = 0;
      // The same surface marched again from a seed the first mesh missed by more than cover_distance
      // (its triangles cut a tight bend there): dropped.
      if (remeshes_earlier(part.mesh, out.mesh, earlier, proximity_radius / 2)) {
        ++out.duplicates;
      } else {
        if (++out.components > max_components)
          throw AlgorithmError("seeding: more than " + std::to_string(max_components) +
                               " components; the level set is fragmented (raise max_components if intended)");
        const int offset = static_cast<int>(out.mesh.vertices.size());
        for (std::size_t v = 0; v < part.mesh.vertices.size(); ++v)
          earlier.insert(offset + static_cast<int>(v), part.mesh.vertices[v]);
        append_mesh(out.mesh, part.mesh);
      }
    }
    std::size_t w = 0;
    for (std::size_t i = 0; i < remaining.size(); ++i)
      if (keep[i]) remaining[w++] = remaining[i];
    remaining.resize(w);
  }
  return out;
}

}  // namespace dtsl
