// Hole fill by fairing (ours; Liepa, "Filling holes in meshes", SGP 2003; Botsch & Kobbelt's
// membrane / thin-plate fairing): the vertices with no data near them are moved to minimise a discrete
// Laplacian energy with every other vertex fixed. The harmonic fill of the displacements
// (hole_fill.hpp) keeps the base surface's shape inside a hole, and Phase 1 leaves a hole spanned by a
// near-minimal surface: flat across a plane cut, dented into a convex part. Thin-plate fairing
// (continuity 1: the bi-Laplacian, tangent-continuous with the two fixed rings around the hole)
// instead continues the surface's slope from the rim, as the shape around it would.
// CGAL::Polygon_mesh_processing::fair (cotangent weights, Voronoi areas) solves each hole, with
// UMFPACK's sparse LU.
#pragma once

#include <cstddef>
#include <vector>

#include "framework/core/types.hpp"

namespace dtsl {

struct HoleFairingReport {
  std::size_t regions = 0;          ///< connected sets of free vertices faired
  std::size_t vertices = 0;         ///< free vertices moved
  std::size_t unanchored = 0;       ///< free vertices of regions without a fixed neighbour (left as they were)
  std::size_t failed_regions = 0;   ///< regions whose solve failed (left as they were)
  std::size_t weakly_anchored_regions = 0;   ///< regions with fewer fixed neighbours than sqrt(their size)
  std::size_t weakly_anchored_vertices = 0;  ///< their free vertices (left as they were)
  std::size_t oversized_regions = 0;  ///< regions above max_region_vertices (left as they were)
  std::size_t oversized_vertices = 0; ///< their free vertices
  std::size_t largest_region = 0;   ///< free vertices of the largest region, faired or not
};

/// Fairs the vertices with free[v] != 0, region by region (connected through `neighbours`), with the
/// other vertices fixed; continuity 0 (membrane: Laplacian), 1 (thin plate: bi-Laplacian) or 2. A
/// region with no fixed neighbour has nothing to continue and is left as it is, and so is one held by
/// fewer fixed neighbours than the square root of its size (not a hole bounded by data), one whose solve
/// fails or gives non-finite positions, and one with more than `max_region_vertices` free vertices (0: no
/// limit; the sparse LU grows faster than the region: docs/design.md §8), each counted. `mesh` must be a manifold (edges and vertices),
/// consistently oriented triangle mesh without faces that repeat a vertex (AlgorithmError otherwise,
/// before anything moves); its normals, if any, are left to the caller.
HoleFairingReport fair_holes(TriangleMesh& mesh, const std::vector<char>& free,
                             const std::vector<std::vector<int>>& neighbours, int continuity,
                             std::size_t max_region_vertices = 0);

}  // namespace dtsl
