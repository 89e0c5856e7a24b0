#include "algorithms/displacement/hole_fairing.hpp"

#ifndef CGAL_EIGEN3_ENABLED
#define CGAL_EIGEN3_ENABLED  // fair() solves with Eigen's SparseLU; Eigen is already a dependency of the core
#endif
#include <CGAL/Polygon_mesh_processing/fair.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "framework/core/connected_components.hpp"
#include "framework/core/error.hpp"

namespace dtsl {

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;

}  // namespace

HoleFairingReport fair_holes(TriangleMesh& mesh, const std::vector<char>& free,
                             const std::vector<std::vector<int>>& neighbours, int continuity,
                             std::size_t max_region_vertices) {
  const std::size_t nv = mesh.vertices.size();
  if (free.size() != nv || neighbours.size() != nv)
    throw AlgorithmError("hole fairing: " + std::to_string(free.size()) + " free flags and " +
                         std::to_string(neighbours.size()) + " neighbour lists for " + std::to_string(nv) +
                         " vertices");
  if (continuity < 0 || continuity > 2)
    throw AlgorithmError("hole fairing: continuity must be 0, 1 or 2, got " + std::to_string(continuity));
  HoleFairingReport report;

  // The regions: connected free vertices, each with the fixed vertices next to it (its rim).
  const std::vector<std::vector<int>> regions = connected_groups(neighbours, free);
  std::vector<int> rim_of(nv, -1);
  std::vector<std::size_t> rim(regions.size(), 0);
  for (std::size_t id = 0; id < regions.size(); ++id)
    for (int v : regions[id])
      for (int u : neighbours[v])
        if (!free[u] && rim_of[u] != static_cast<int>(id)) rim_of[u] = static_cast<int>(id), ++rim[id];
  // A hole in sampled data is bounded by data: a disc of n vertices has ~3.5 sqrt(n) on its rim, a strip
  // more. A region held by fewer than sqrt(n) fixed vertices is a surface with a few data points on it
  // (a degenerate input: 67k free vertices, 13 fixed); fairing it would invent its shape from those few,
  // at a sparse LU's cost.
  std::vector<char> solve(regions.size(), 0);
  for (std::size_t i = 0; i < regions.size(); ++i) {
    const std::size_t n = regions[i].size();
    report.largest_region = std::max(report.largest_region, n);
    if (rim[i] == 0) {
      report.unanchored += n;
    } else if (static_cast<double>(rim[i]) < std::sqrt(static_cast<double>(n))) {
      ++report.weakly_anchored_regions;
      report.weakly_anchored_vertices += n;
    } else if (max_region_vertices > 0 && n > max_region_vertices) {
      ++report.oversized_regions;
      report.oversized_vertices += n;
    } else {
      solve[i] = 1;
    }
  }
  if (std::find(solve.begin(), solve.end(), 1) == solve.end()) return report;

  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> handle(nv);
  for (std::size_t v = 0; v < nv; ++v) {
    const Vec3& p = mesh.vertices[v];
    handle[v] = sm.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z()));
  }
  for (std::size_t fi = 0; fi < mesh.faces.size(); ++fi) {
    const Face& f = mesh.faces[fi];
    if (sm.add_face(handle[f[0]], handle[f[1]], handle[f[2]]) == SurfaceMesh::null_face())
      throw AlgorithmError("hole fairing: face " + std::to_string(fi) +
                           " makes the mesh non-manifold or inconsistently oriented");
  }
  // Deterministic: regions in the order of their first vertex, one solve each. A region's rows reach k+1
  // rings out, so one within that reach of an earlier region sees its faired positions (fixed).
  for (std::size_t i = 0; i < regions.size(); ++i) {
    if (!solve[i]) continue;
    std::vector<SurfaceMesh::Vertex_index> vs;
    vs.reserve(regions[i].size());
    for (int v : regions[i]) vs.push_back(handle[v]);
    const bool solved = CGAL::Polygon_mesh_processing::fair(sm, vs, CGAL::parameters::fairing_continuity(continuity));
    // fair() moves nothing when its solve fails, but does not check a solve that "succeeds": a zero-length
    // edge or a zero Voronoi area near the region gives NaN weights. Such a region keeps its positions.
    bool finite = solved;
    for (int v : regions[i]) {
      const Kernel::Point_3& p = sm.point(handle[v]);
      finite = finite && std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
    }
    if (!finite) {
      ++report.failed_regions;
      for (int v : regions[i]) {
        const Vec3& p = mesh.vertices[v];
        sm.point(handle[v]) = Kernel::Point_3(p.x(), p.y(), p.z());
      }
      continue;
    }
    ++report.regions;
    report.vertices += regions[i].size();
  }
  for (std::size_t v = 0; v < nv; ++v) {
    if (!free[v]) continue;
    const Kernel::Point_3& p = sm.point(handle[v]);
    mesh.vertices[v] = Vec3(p.x(), p.y(), p.z());
  }
  return report;
}

}  // namespace dtsl
