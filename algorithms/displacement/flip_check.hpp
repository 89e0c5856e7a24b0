// The flip check of the displaced mesh (paper §3.2: "the allowed displacement can be bounded with the
// help of the principal curvature radii"): a vertex whose |d(v)| towards a centre of curvature reaches
// half the radius there is at risk, and the triangles of its one-ring (and of every faired hole vertex,
// which also moves tangentially) are tested for a reversed normal. A flip asks the pipeline to refine
// the level set near it and displace again (refine_on_flip.hpp).
#pragma once

#include <vector>

#include "algorithms/displacement/curvature.hpp"
#include "algorithms/displacement/projection.hpp"
#include "framework/core/types.hpp"

namespace dtsl {

struct FlipCheck {
  std::vector<int> at_risk_vertices;   ///< |d(v)| towards a centre of curvature >= half its radius
  std::vector<int> flipped_faces;      ///< faces whose normal reversed (among those tested)
  std::vector<int> flipped_vertices;   ///< vertices of flipped faces: where to refine the level set
  std::size_t faces_tested = 0;
};

/// `base` displaced to `displaced` by d along the normals; `curvatures` of f at the base vertices;
/// `locator`: of `base` (its vertex-face adjacency); `faired` vertices' faces are tested too.
FlipCheck check_flips(const TriangleMesh& base, const std::vector<Vec3>& displaced, const std::vector<double>& d,
                      const std::vector<PrincipalCurvatures>& curvatures,
                      const MeshLocator& locator, const std::vector<int>& faired);

}  // namespace dtsl
