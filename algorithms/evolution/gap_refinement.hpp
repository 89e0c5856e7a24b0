// Narrow gaps between separate pieces of the data (ours). The carving opens the space between pieces
// (data_carving.hpp) and the evolution holds the controls there positive (hold_outside, sign_guard.hpp),
// but a cubic T-spline cannot change sign twice across a gap narrower than about two of its cells: its
// value in the gap blends controls on both sides, the positive ones in the gap are outweighed by the
// negative ones inside the two objects, and the zero set stays one neck across. Two tori 1.3 finest
// cells apart (the topology suite's pair_tori_gap5) came out one component; the same data on a T-mesh one
// level finer everywhere came out two, at 2.7x the time (docs/design.md §8). So the leaves a narrow gap
// crosses are split once more, one level below the finest, and the rest of the T-mesh is left alone.
//
// A gap is narrow when a data point's nearest point on another piece is closer than kNarrowGapCells
// finest cells; the leaves holding the segment between the two points are split to one level below
// the T-mesh's finest leaf, the octree's lattice deepened by a level when that is past its max_depth.
#pragma once

#include <vector>

#include "algorithms/tspline/octree.hpp"
#include "framework/core/types.hpp"

namespace dtsl {

/// A gap narrower than this many finest leaf sides is refined.
constexpr double kNarrowGapCells = 2.0;

/// The same leaves on a lattice one level finer (max_depth + 1): the T-mesh and its T-spline space are
/// unchanged, and every leaf may be split once more. AlgorithmError past kMaxOctreeDepth.
Octree deepened(const Octree& tree);

struct GapRefinement {
  int narrow_pairs = 0;   ///< data points whose nearest point on another piece is within the narrow gap
  int split_leaves = 0;   ///< leaves split (before rebalancing)
  int level = 0;          ///< the level they were split to
  double seconds = 0.0;
};

/// `tree` with the leaves that narrow gaps between the pieces of `points` (piece[i] is point i's, as
/// DataCarving::pieces()) cross split to one level below its finest leaf, rebalanced; `tree` itself
/// (and split_leaves 0) when no gap is narrow. AlgorithmError when the sizes differ or a label is negative.
Octree refine_narrow_gaps(const Octree& tree, const std::vector<Vec3>& points, const std::vector<int>& piece,
                          GapRefinement* report = nullptr);

}  // namespace dtsl
