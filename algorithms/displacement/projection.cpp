// Paper §3.1: foot points, signed displacements, closest triangles through the closest vertex's one-ring.
#include "algorithms/displacement/projection.hpp"

#include <algorithm>
#include <cmath>

#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"

namespace dtsl {

const char* to_string(ProjectionCase c) {
  switch (c) {
    case ProjectionCase::vertex: return "vertex";
    case ProjectionCase::edge: return "edge";
    case ProjectionCase::face: return "face";
    default: return "none";
  }
}

void LocatorOptions::visit(FieldVisitor& v) {
  v.field("grid_cell", grid_cell, "closest-vertex grid cell, x the mesh's mean edge length");
  v.field("snap_tolerance", snap_tolerance,
          "a barycentric coordinate below this counts as 0 (closest point on an edge / vertex: all its triangles)");
}
void LocatorOptions::check() const {
  check_range("grid_cell", grid_cell, 0.1, 100.0);
  check_range("snap_tolerance", snap_tolerance, 0.0, 0.1);
}

void ProjectionOptions::visit(FieldVisitor& v) {
  v.field("newton_tolerance", newton_tolerance, "Newton foot points: stop when |f|/|grad f| is below this (frame units)");
  v.field("newton_max_iterations", newton_max_iterations, "Newton foot points: iteration cap (not converged: point left out)");
  v.field("newton_max_step", newton_max_step, "longest Newton step x mean edge length (0 = unclamped, the paper's step)");
  locator.visit(v);
}
void ProjectionOptions::check() const {
  check_positive("newton_tolerance", newton_tolerance);
  check_range("newton_max_iterations", newton_max_iterations, 1, 10000);
  check_non_negative("newton_max_step", newton_max_step);
  locator.check();
}

// Ericson §5.1.5, with the barycentric coordinates of every region.
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& bary) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return bary = Vec3(1, 0, 0), a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bary = Vec3(0, 1, 0), b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    bary = Vec3(1 - v, v, 0);
    return a + v * ab;
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return bary = Vec3(0, 0, 1), c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    bary = Vec3(1 - w, 0, w);
    return a + w * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    bary = Vec3(0, 1 - w, w);
    return b + w * (c - b);
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  bary = Vec3(1 - v - w, v, w);
  return a + ab * v + ac * w;
}

MeshLocator::MeshLocator(const TriangleMesh& mesh, const LocatorOptions& options) : mesh_(&mesh), options_(options) {
  options_.check();
  if (mesh.faces.empty() || mesh.vertices.empty()) throw AlgorithmError("mesh projection: the mesh has no faces");
  check_finite(mesh, "mesh projection");
  adjacency_ = mesh_adjacency(mesh, "mesh projection");
  // The mean over every face side (an inner edge counts twice, a boundary edge once).
  double total = 0.0;
  std::size_t edges = 0;
  for (const Face& f : mesh.faces)
    for (int k = 0; k < 3; ++k, ++edges) total += (mesh.vertices[f[k]] - mesh.vertices[f[(k + 1) % 3]]).norm();
  mean_edge_ = total / static_cast<double>(edges);
  if (!(mean_edge_ > 0)) throw AlgorithmError("mesh projection: every edge of the mesh has length 0");
  grid_ = PointGrid(mesh.vertices, options_.grid_cell * mean_edge_);
}

MeshLocation MeshLocator::one_ring(const Vec3& q, int vertex) const {
  MeshLocation best;
  best.closest_vertex = vertex;
  best.distance = std::numeric_limits<double>::infinity();
  const auto& V = mesh_->vertices;
  for (int fi : adjacency_.vertex_faces[vertex]) {
    const Face& f = mesh_->faces[fi];
    Vec3 bary;
    const Vec3 x = closest_point_on_triangle(q, V[f[0]], V[f[1]], V[f[2]], bary);
    const double d = (x - q).norm();
    if (d < best.distance) {
      best.distance = d;
      best.point = x;
      best.face = fi;
      best.barycentric = bary;
    }
  }
  if (best.face < 0) {  // an isolated vertex: the vertex itself is the answer, no triangle
    best.point = V[vertex];
    best.distance = (q - V[vertex]).norm();
    return best;
  }
  // Snap tiny coordinates to 0 so a point within rounding of an edge / vertex gets that case.
  Vec3& w = best.barycentric;
  for (int k = 0; k < 3; ++k)
    if (w[k] < options_.snap_tolerance) w[k] = 0.0;
  w /= w.sum();
  const Face& f = mesh_->faces[best.face];
  const int nonzero = (w.array() > 0).count();
  if (nonzero == 3) {
    best.kind = ProjectionCase::face;
  } else if (nonzero == 2) {
    best.kind = ProjectionCase::edge;
    int e = 0;
    for (int k = 0; k < 3; ++k)
      if (w[k] > 0) best.element[e++] = f[k];
    if (best.element[0] > best.element[1]) std::swap(best.element[0], best.element[1]);
  } else {
    best.kind = ProjectionCase::vertex;
    for (int k = 0; k < 3; ++k)
      if (w[k] > 0) best.element[0] = f[k];
  }
  return best;
}

MeshLocation MeshLocator::locate(const Vec3& q) const { return one_ring(q, grid_.nearest(q)); }

MeshLocation MeshLocator::locate_from(const Vec3& q, int v) const {
  if (v < 0 || v >= static_cast<int>(mesh_->vertices.size())) return locate(q);
  double dv = (mesh_->vertices[v] - q).squaredNorm();
  for (bool moved = true; moved;) {  // greedy descent on the vertex graph
    moved = false;
    for (int n : adjacency_.vertex_neighbours[v]) {
      const double dn = (mesh_->vertices[n] - q).squaredNorm();
      if (dn < dv) dv = dn, v = n, moved = true;
    }
  }
  return one_ring(q, v);
}

std::vector<int> MeshLocator::closest_faces(const MeshLocation& loc) const {
  switch (loc.kind) {
    case ProjectionCase::face: return {loc.face};
    case ProjectionCase::vertex: return adjacency_.vertex_faces[loc.element[0]];
    case ProjectionCase::edge: {
      std::vector<int> out;
      for (int fi : adjacency_.vertex_faces[loc.element[0]]) {
        const Face& f = mesh_->faces[fi];
        if (f[0] == loc.element[1] || f[1] == loc.element[1] || f[2] == loc.element[1]) out.push_back(fi);
      }
      return out;
    }
    default: return {};
  }
}

nlohmann::json ProjectionResult::summary() const {
  return {{"points", foot_points.size()},
          {"newton_failures", newton_failures},
          {"case_vertex", cases[static_cast<int>(ProjectionCase::vertex)]},
          {"case_edge", cases[static_cast<int>(ProjectionCase::edge)]},
          {"case_face", cases[static_cast<int>(ProjectionCase::face)]},
          {"seconds", seconds}};
}

ProjectionResult project_data(const ImplicitFunction& f, const MeshLocator& locator, const std::vector<Vec3>& points,
                              const ProjectionOptions& options) {
  options.check();
  if (points.empty()) throw AlgorithmError("displacement projection: no data points");
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite())
      throw AlgorithmError("displacement projection: data point " + std::to_string(i) + " is not finite");
  Stopwatch timer;
  NewtonOptions newton;
  newton.tolerance = options.newton_tolerance;
  newton.max_iterations = options.newton_max_iterations;
  if (options.newton_max_step > 0) newton.max_step = options.newton_max_step * locator.mean_edge_length();
  // Steps 3.1-3.3: Newton foot points (the polygonizers' projection, parallel inside).
  const std::vector<NewtonProjection> feet = newton_project_all(f, points, newton);

  const std::size_t n = points.size();
  ProjectionResult r;
  r.foot_points.resize(n);
  r.foot_normals.resize(n);
  r.displacements.assign(n, 0.0);
  r.valid.assign(n, 0);
  r.locations.resize(n);
#pragma omp parallel for schedule(dynamic, 256)
  for (long k = 0; k < static_cast<long>(n); ++k) {
    const NewtonProjection& np = feet[k];
    r.foot_points[k] = np.point;
    if (!np.converged() || !np.point.allFinite()) continue;
    r.foot_normals[k] = np.normal();
    // Step 3.4: d_k = sign(f(p_k)) |p_k - q_k| (f < 0 inside: a point inside moves the surface inward).
    const double fp = f.value(points[k]);
    r.displacements[k] = (fp < 0 ? -1.0 : 1.0) * (points[k] - np.point).norm();
    // Steps 3.5-3.6: closest vertex, then the closest triangle(s) of its one-ring.
    r.locations[k] = locator.locate(np.point);
    r.valid[k] = r.locations[k].found();
  }
  // Steps 1 and 3.7: the per-triangle index lists I_i (serial: appends in point order, deterministic).
  r.triangle_points.assign(locator.mesh().faces.size(), {});
  for (std::size_t k = 0; k < n; ++k) {
    if (!r.valid[k]) {
      ++r.newton_failures;
      continue;
    }
    ++r.cases[static_cast<int>(r.locations[k].kind)];
    for (int fi : locator.closest_faces(r.locations[k])) r.triangle_points[fi].push_back(static_cast<int>(k));
  }
  r.seconds = timer.seconds();
  return r;
}

}  // namespace dtsl
