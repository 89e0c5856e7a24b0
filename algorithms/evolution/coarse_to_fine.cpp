#include "algorithms/evolution/coarse_to_fine.hpp"

#include <algorithm>

#include "algorithms/evolution/data_distance.hpp"
#include "algorithms/evolution/level_set_transfer.hpp"
#include "algorithms/evolution/zero_set.hpp"

namespace dtsl {

TSpline refine_toward_data(const TSpline& f, const std::vector<Vec3>& points, int level,
                           const CoarseToFineOptions& options) {
  options.check();
  const Octree& tree = f.tmesh();
  level = std::min(level, tree.max_depth());
  std::vector<int> count(tree.leaf_count(), 0);
  for (const Vec3& p : points) ++count[tree.locate(p)];
  std::vector<int> split;
  for (int l = 0; l < tree.leaf_count(); ++l)
    if (tree.leaf(l).level < level && count[l] >= options.points_per_cell) split.push_back(l);
  if (options.data_reach > 0.0) {
    const DataDistance data(points);
    ZeroSetSampling sampling;
    sampling.hessians = false;
    const ZeroSetSamples samples = sample_zero_set(f, tree, sampling);
    for (const SurfacePoint& s : samples.surface) {
      if (tree.leaf(s.leaf).level >= level) continue;
      if (data.nearest(s.position).distance <= options.data_reach * s.cell_size) split.push_back(s.leaf);
    }
  }
  std::sort(split.begin(), split.end());
  split.erase(std::unique(split.begin(), split.end()), split.end());
  if (split.empty()) return f;
  return transfer_level_set(f, refine_octree(tree, split, balance_of(tree)));
}

}  // namespace dtsl
