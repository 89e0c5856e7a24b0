#include "algorithms/displacement/hole_fairing.hpp"

#ifndef CGAL_EIGEN3_ENABLED
#define CGAL_EIGEN3_ENABLED  // fair()'s solver traits wrap Eigen; Eigen is already a dependency of the core
#endif
#include <CGAL/Eigen_solver_traits.h>
#include <CGAL/Polygon_mesh_processing/fair.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <Eigen/UmfPackSupport>

#include <algorithm>
#include <cmath>
#include <string>

#include "framework/core/connected_components.hpp"
#include "framework/core/error.hpp"

namespace dtsl {

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using LuSolver = CGAL::Eigen_solver_traits<Eigen::UmfPackLU<CGAL::Eigen_sparse_matrix<double>::EigenType>>;

// Connected free vertices, each region with the number of fixed vertices next to it (its rim).
struct FreeRegions {
  std::vector<std::vector<int>> vertices;
  std::vector<std::size_t> rim;
};

FreeRegions free_regions(const std::vector<char>& free, const std::vector<std::vector<int>>& neighbours) {
  FreeRegions out;
  out.vertices = connected_groups(neighbours, free);
  out.rim.assign(out.vertices.size(), 0);
  std::vector<int> rim_of(free.size(), -1);
  for (std::size_t id = 0; id < out.vertices.size(); ++id)
    for (int v : out.vertices[id])
      for (int u : neighbours[v])
        if (!free[u] && rim_of[u] != static_cast<int>(id)) rim_of[u] = static_cast<int>(id), ++out.rim[id];
  return out;
}

// Which regions to fair. A hole in sampled data is bounded by data: a disc of n vertices has
// ~3.5 sqrt(n) on its rim, a strip more. A region held by fewer than sqrt(n) fixed vertices is a surface
// with a few data points on it (a degenerate input: 67k free vertices, 13 fixed); fairing it would
// invent its shape from those few, at a sparse LU's cost.
std::vector<char> regions_to_fair(const FreeRegions& regions, std::size_t max_region_vertices,
                                  HoleFairingReport& report) {
  std::vector<char> solve(regions.vertices.size(), 0);
  for (std::size_t i = 0; i < regions.vertices.size(); ++i) {
    const std::size_t n = regions.vertices[i].size();
    report.largest_region = std::max(report.largest_region, n);
    if (regions.rim[i] == 0) {
      report.unanchored += n;
    } else if (static_cast<double>(regions.rim[i]) < std::sqrt(static_cast<double>(n))) {
      ++report.weakly_anchored_regions;
      report.weakly_anchored_vertices += n;
    } else if (max_region_vertices > 0 && n > max_region_vertices) {
      ++report.oversized_regions;
      report.oversized_vertices += n;
    } else {
      solve[i] = 1;
    }
  }
  return solve;
}

SurfaceMesh surface_mesh(const TriangleMesh& mesh, std::vector<SurfaceMesh::Vertex_index>& handle) {
  SurfaceMesh sm;
  handle.resize(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const Vec3& p = mesh.vertices[v];
    handle[v] = sm.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z()));
  }
  for (std::size_t fi = 0; fi < mesh.faces.size(); ++fi) {
    const Face& f = mesh.faces[fi];
    if (sm.add_face(handle[f[0]], handle[f[1]], handle[f[2]]) == SurfaceMesh::null_face())
      throw AlgorithmError("hole fairing: face " + std::to_string(fi) +
                           " makes the mesh non-manifold or inconsistently oriented");
  }
  return sm;
}

// Fairs one region of `sm`; false (its positions restored from `mesh`) when the solve fails.
bool fair_region(SurfaceMesh& sm, const std::vector<SurfaceMesh::Vertex_index>& handle, const TriangleMesh& mesh,
                 const std::vector<int>& region, int continuity) {
  std::vector<SurfaceMesh::Vertex_index> vs;
  vs.reserve(region.size());
  for (int v : region) vs.push_back(handle[v]);
  // The system is not symmetric (Voronoi-area-weighted cotangent Laplacians), so an LU: UMFPACK's
  // factorises the regions of sparse data (tens of thousands of free vertices) faster than fair()'s
  // default, Eigen's SparseLU, on most of the suite's inputs (docs/performance.md).
  LuSolver lu;
  const bool solved = CGAL::Polygon_mesh_processing::fair(
      sm, vs, CGAL::parameters::fairing_continuity(continuity).sparse_linear_solver(lu));
  // fair() moves nothing when its solve fails, but does not check a solve that "succeeds": a zero-length
  // edge or a zero Voronoi area near the region gives NaN weights. Such a region keeps its positions.
  bool finite = solved;
  for (int v : region) {
    const Kernel::Point_3& p = sm.point(handle[v]);
    finite = finite && std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
  }
  if (finite) return true;
  for (int v : region) {
    const Vec3& p = mesh.vertices[v];
    sm.point(handle[v]) = Kernel::Point_3(p.x(), p.y(), p.z());
  }
  return false;
}

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
  const FreeRegions regions = free_regions(free, neighbours);
  const std::vector<char> solve = regions_to_fair(regions, max_region_vertices, report);
  if (std::find(solve.begin(), solve.end(), 1) == solve.end()) return report;
  std::vector<SurfaceMesh::Vertex_index> handle;
  SurfaceMesh sm = surface_mesh(mesh, handle);
  // Deterministic: regions in the order of their first vertex, one solve each. A region's rows reach k+1
  // rings out, so one within that reach of an earlier region sees its faired positions (fixed).
  for (std::size_t i = 0; i < regions.vertices.size(); ++i) {
    if (!solve[i]) continue;
    if (!fair_region(sm, handle, mesh, regions.vertices[i], continuity)) {
      ++report.failed_regions;
      continue;
    }
    ++report.regions;
    report.vertices += regions.vertices[i].size();
  }
  for (std::size_t v = 0; v < nv; ++v) {
    if (!free[v]) continue;
    const Kernel::Point_3& p = sm.point(handle[v]);
    mesh.vertices[v] = Vec3(p.x(), p.y(), p.z());
  }
  return report;
}

}  // namespace dtsl
