#include "algorithms/displacement/flip_check.hpp"

#include <algorithm>

namespace dtsl {

namespace {

// |d(v)| towards a centre of curvature at this fraction of the radius puts v at risk. Only a radius whose
// centre lies on the displacement's side counts (inward on convex, outward on concave parts: the paper's
// "deep convex or concave parts"); moving away from it cannot make the normals cross.
constexpr double kCurvatureFraction = 0.5;

}  // namespace

FlipCheck check_flips(const TriangleMesh& base, const std::vector<Vec3>& displaced, const std::vector<double>& d,
                      const std::vector<PrincipalCurvatures>& curvatures,
                      const MeshLocator& locator, const std::vector<int>& faired) {
  FlipCheck r;
  const std::size_t nv = base.vertices.size();
  std::vector<char> candidate(base.faces.size(), 0);
  for (std::size_t v = 0; v < nv; ++v) {
    // d k_i = -1 where v reaches the centre of curvature i (k > 0 convex, n outward).
    const PrincipalCurvatures& c = curvatures[v];
    const double reach = c.valid ? std::max({-d[v] * c.k1, -d[v] * c.k2, 0.0}) : 0.0;
    if (reach > 0 && reach >= kCurvatureFraction) {
      r.at_risk_vertices.push_back(static_cast<int>(v));
      for (int fi : locator.vertex_faces(static_cast<int>(v))) candidate[fi] = 1;
    }
  }
  for (int v : faired)
    for (int fi : locator.vertex_faces(static_cast<int>(v))) candidate[fi] = 1;
  std::vector<int> candidates;
  for (std::size_t fi = 0; fi < candidate.size(); ++fi)
    if (candidate[fi]) candidates.push_back(static_cast<int>(fi));
  r.faces_tested = candidates.size();
  r.flipped_faces = flipped_faces(base, displaced, &candidates);
  std::vector<char> flipped(nv, 0);
  for (int fi : r.flipped_faces)
    for (int k = 0; k < 3; ++k) flipped[base.faces[fi][k]] = 1;
  for (std::size_t v = 0; v < nv; ++v)
    if (flipped[v]) r.flipped_vertices.push_back(static_cast<int>(v));
  return r;
}

}  // namespace dtsl
