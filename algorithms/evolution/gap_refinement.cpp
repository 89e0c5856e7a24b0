// Narrow gaps between separate pieces of the data: gap_refinement.hpp.
#include "algorithms/evolution/gap_refinement.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "algorithms/evolution/data_distance.hpp"
#include "algorithms/evolution/level_set_transfer.hpp"
#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"

namespace dtsl {

Octree deepened(const Octree& tree) {
  if (tree.max_depth() + 1 > kMaxOctreeDepth)
    throw AlgorithmError("deepened: the octree is already at the deepest lattice (" + std::to_string(kMaxOctreeDepth) +
                         " levels)");
  std::vector<LeafRecord> leaves;
  leaves.reserve(std::size_t(tree.leaf_count()));
  for (int l = 0; l < tree.leaf_count(); ++l) {
    const Octree::Cell& c = tree.leaf(l);
    leaves.push_back({c.level, {2 * c.origin[0], 2 * c.origin[1], 2 * c.origin[2]}});
  }
  return octree_from_leaves(tree.domain_min(), tree.side(), tree.max_depth() + 1, leaves);
}

namespace {

/// `tree` with the leaves holding any of `samples` split until they are at `level` (rebalanced), the
/// lattice deepened when `level` is past max_depth; `split_leaves` counts the splits.
Octree split_to_level(const Octree& tree, const std::vector<Vec3>& samples, int level, int* split_leaves) {
  Octree refined = level > tree.max_depth() ? deepened(tree) : tree;
  // One split per pass: a sample in a leaf coarser than level - 1 takes more than one.
  const Balance balance = balance_of(tree);
  int splits = 0;
  for (int pass = 0; pass <= level; ++pass) {
    std::vector<int> split;
    for (const Vec3& x : samples) {
      const int leaf = refined.locate(x);
      if (refined.leaf(leaf).level < level) split.push_back(leaf);
    }
    std::sort(split.begin(), split.end());
    split.erase(std::unique(split.begin(), split.end()), split.end());
    if (split.empty()) break;
    splits += int(split.size());
    refined = refine_octree(refined, split, balance);
  }
  if (split_leaves) *split_leaves = splits;
  return refined;
}

/// The segments between data points and their nearest point on another piece, where shorter than `gap`.
std::vector<std::pair<Vec3, Vec3>> narrow_gaps(const std::vector<Vec3>& points, const std::vector<int>& piece,
                                               double gap) {
  const int pieces = piece.empty() ? 0 : *std::max_element(piece.begin(), piece.end()) + 1;
  std::vector<std::pair<Vec3, Vec3>> segments;
  if (pieces < 2) return segments;
  const auto count = std::size_t(pieces);
  std::vector<std::vector<Vec3>> members(count);
  std::vector<BoundingBox> boxes(count);
  for (std::size_t i = 0; i < points.size(); ++i) {
    members[std::size_t(piece[i])].push_back(points[i]);
    boxes[std::size_t(piece[i])].extend(points[i]);
  }
  std::vector<std::unique_ptr<DataDistance>> trees(count);
  for (std::size_t b = 0; b < count; ++b)
    if (!members[b].empty()) trees[b] = std::make_unique<DataDistance>(members[b]);
  // Per point, then joined in point order: the same segments for any thread count.
  std::vector<std::vector<std::pair<Vec3, Vec3>>> per_point(points.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (long i = 0; i < long(points.size()); ++i) {
    const Vec3& p = points[std::size_t(i)];
    for (int b = 0; b < pieces; ++b) {
      if (b == piece[std::size_t(i)] || !trees[std::size_t(b)]) continue;
      const BoundingBox& box = boxes[std::size_t(b)];
      if (((p - box.max).array() > gap).any() || ((box.min - p).array() > gap).any()) continue;
      const NearestData q = trees[std::size_t(b)]->nearest(p);
      if (q.distance < gap) per_point[std::size_t(i)].emplace_back(p, members[std::size_t(b)][std::size_t(q.index)]);
    }
  }
  for (const auto& found : per_point) segments.insert(segments.end(), found.begin(), found.end());
  return segments;
}

}  // namespace

Octree refine_narrow_gaps(const Octree& tree, const std::vector<Vec3>& points, const std::vector<int>& piece,
                          GapRefinement* report) {
  if (piece.size() != points.size())
    throw AlgorithmError("refine_narrow_gaps: " + std::to_string(piece.size()) + " piece labels for " +
                         std::to_string(points.size()) + " points");
  for (std::size_t i = 0; i < piece.size(); ++i)
    if (piece[i] < 0) throw AlgorithmError("refine_narrow_gaps: point " + std::to_string(i) + " has no piece");
  Stopwatch clock;
  GapRefinement r;
  const int finest = tree.finest_leaf_level();
  r.level = finest + 1;
  const double finest_side = tree.unit() * double(tree.cell_size(finest));
  const std::vector<std::pair<Vec3, Vec3>> segments = narrow_gaps(points, piece, kNarrowGapCells * finest_side);
  r.narrow_pairs = int(segments.size());
  if (segments.empty() || r.level > kMaxOctreeDepth) {
    r.seconds = clock.seconds();
    if (report) *report = r;
    return tree;
  }
  // Each segment sampled at a quarter of the target level's side, so every leaf it crosses holds a sample.
  const double step = 0.25 * finest_side / 2.0;
  std::vector<Vec3> samples;
  for (const auto& [p, q] : segments) {
    const int n = std::max(1, int(std::ceil((q - p).norm() / step)));
    for (int k = 0; k <= n; ++k) samples.push_back(p + (q - p) * (double(k) / double(n)));
  }
  const Octree refined = split_to_level(tree, samples, r.level, &r.split_leaves);
  r.seconds = clock.seconds();
  if (report) *report = r;
  return refined;
}

}  // namespace dtsl
