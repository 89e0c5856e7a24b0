#include "algorithms/evolution/thin_walls.hpp"

#include <cmath>
#include <cstddef>

namespace dtsl {

namespace {

constexpr double kCone = 0.70710678118654752;  // cos 45 degrees: q lies behind p
constexpr double kFacingAway = -0.5;           // n_p . n_q at most this: the other face
constexpr double kThrough = 0.5;               // at most this many leaf sides from the march: on its path
constexpr int kStepsPerLeaf = 4;               // the march's step: a quarter of the leaf at p
constexpr double kOwnFace = 0.5;               // n_p . n_q at least this: p's own face

}  // namespace

ThinWalls thin_walls(const std::vector<Vec3>& points, const DataDistance& data, const ImplicitFunction& start,
                     const Octree& tmesh) {
  const long n = long(points.size());
  std::vector<Vec3> normal(points.size(), Vec3::Zero());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    Vec3 g;
    start.evaluate(points[std::size_t(i)], &g);
    const double length = g.norm();
    if (std::isfinite(length) && length > 0.0) normal[std::size_t(i)] = g / length;
  }
  std::vector<int> partner(points.size(), -1);
#pragma omp parallel for schedule(dynamic, 256)
  for (long i = 0; i < n; ++i) {
    const Vec3& p = points[std::size_t(i)];
    const Vec3& np = normal[std::size_t(i)];
    if (np.squaredNorm() == 0.0) continue;
    const double side = tmesh.leaf_side(tmesh.locate(p));
    const double farthest = kMaxWallCells * side;
    const double step = side / kStepsPerLeaf;
    int crossed = -1;  // the step at which the march passed through a face turned partly away
    for (int k = 1; k <= int(kMaxWallCells * kStepsPerLeaf); ++k) {
      if (crossed >= 0 && k - crossed > kStepsPerLeaf) break;  // one leaf past that face, no farther
      const NearestData nearest = data.nearest(p - (k * step) * np);
      const int q = nearest.index;
      if (q < 0 || q == int(i)) continue;
      const Vec3 v = points[std::size_t(q)] - p;
      const double d = v.norm();
      if (d > farthest || -v.dot(np) < kCone * d) continue;
      const double facing = normal[std::size_t(q)].dot(np);
      if (facing <= kFacingAway) {
        partner[std::size_t(i)] = q;
        break;
      }
      // Passing through a face behind p (q on the march's path) that is not p's own face curving along
      // it (normals within 60 degrees of n_p): where that face is turned sideways or the same way as
      // p's (or q has no normal), the march has left the part through the side the start covered over,
      // and what lies beyond is not this wall's far face. A face turned partly away may be the far face
      // with tilted normals: the march goes on for one leaf past it, no farther.
      if (nearest.distance <= kThrough * side && facing < kOwnFace) {
        if (facing >= 0.0) break;
        if (crossed < 0) crossed = k;
      }
    }
  }
  ThinWalls walls;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (partner[i] < 0) continue;
    const Vec3& q = points[std::size_t(partner[i])];
    walls.middle.push_back(0.5 * (points[i] + q));
    walls.depth.push_back(0.25 * (q - points[i]).norm());
  }
  return walls;
}

WallRows wall_rows(const ThinWalls& walls, const ImplicitFunction& f, double dt) {
  const long n = long(walls.size());
  std::vector<double> value(walls.size());
#pragma omp parallel for schedule(static)
  for (long m = 0; m < n; ++m) value[std::size_t(m)] = f.evaluate(walls.middle[std::size_t(m)]);
  WallRows rows;
  for (std::size_t m = 0; m < walls.size(); ++m) {
    if (!(value[m] > -walls.depth[m])) continue;
    rows.position.push_back(walls.middle[m]);
    rows.target.push_back((-walls.depth[m] - value[m]) / dt);
  }
  return rows;
}

}  // namespace dtsl
