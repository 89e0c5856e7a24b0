// Degenerate-triangle removal after the bilateral evolution (paper §4.3: sharp vertices gather on the
// sharp edges and leave needles behind; the paper applies MeshSlicing [7], docs/design.md §4 allows a
// library's removal). We collapse every edge shorter than a fraction of the mean edge length with CGAL's
// Euler::collapse_edge, only where the link condition holds (the mesh stays closed and 2-manifold) and
// no surviving triangle around the merged vertex would flip or become degenerate. The merged vertex
// keeps the position of a sharp endpoint (it lies on a recovered edge), else the midpoint.
#pragma once

#include <cstddef>
#include <vector>

#include "framework/config/options.hpp"
#include "framework/core/types.hpp"

namespace dtsl::sharpen {

struct DegenerateRemovalOptions final : Options {
  /// Collapse edges shorter than this fraction of the mean edge length; 0 turns the step off.
  double min_edge_ratio = 0.2;
  /// Also collapse the shortest edge of a triangle whose smallest angle is below this (degrees); 0: off.
  double min_angle_deg = 3.0;
  /// Passes over the mesh (a collapse can create a new short edge).
  int max_passes = 5;

  void visit(FieldVisitor& v) override;
  void check() const override;
};

struct DegenerateRemovalReport {
  std::size_t collapsed = 0;  ///< edges collapsed
  std::size_t rejected = 0;   ///< candidate edges left (link condition or a flip would break the mesh)
  std::vector<int> face_origin;  ///< for each output face, its index in the input mesh
};

/// Changes `mesh` in place (vertices renumbered). `sharp` (one flag per vertex, or empty) is carried
/// along and renumbered with the mesh; if it is given, only edges with a flagged endpoint
/// are candidates (the region the evolution moved). `reference_normals` (one per face, or empty): a
/// collapse that would turn a surviving face by 90 degrees or more from its reference is refused (the
/// evolution passes the input mesh's normals, so the end result never flips against its input). Throws AlgorithmError for a mesh CGAL cannot read as a polygon
/// mesh (non-manifold input).
DegenerateRemovalReport remove_degenerate_triangles(TriangleMesh& mesh, std::vector<char>& sharp,
                                                    const DegenerateRemovalOptions& options,
                                                    const std::vector<Vec3>& reference_normals = {});

}  // namespace dtsl::sharpen
