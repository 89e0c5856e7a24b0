// The data's pieces: the connected components of the graph joining every data point to its k nearest
// others (made symmetric). Points of one sampled surface are joined however non-uniform the sampling, as
// each point's neighbourhood is as wide as its own spacing; two surfaces lie in different pieces when the
// gap between them is wider than their points' k-th neighbour distance (about 1.5 local spacings for
// k = kSpacingNeighbours, support.hpp). data_carving.hpp opens the space between pieces.
#pragma once

#include <vector>

#include "algorithms/evolution/data_distance.hpp"

namespace dtsl {

/// Per data point, its piece (the components of the graph of `neighbours`,
/// DataDistance::nearest_neighbours), numbered 0.. in the order of each piece's first point.
std::vector<int> data_pieces(const NearestNeighbours& neighbours);

/// The points of each piece (piece[i] is point i's, 0..), in input order. AlgorithmError when the sizes
/// differ or a label is negative.
std::vector<std::vector<Vec3>> points_by_piece(const std::vector<Vec3>& points, const std::vector<int>& piece);

}  // namespace dtsl
