#include "algorithms/evolution/data_pieces.hpp"

#include <algorithm>

#include "framework/core/error.hpp"
#include "framework/core/union_find.hpp"

namespace dtsl {

std::vector<int> data_pieces(const NearestNeighbours& neighbours) {
  const std::size_t k = std::size_t(neighbours.k), n = k > 0 ? neighbours.index.size() / k : 0;
  UnionFind sets(n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < k; ++j)
      if (const int other = neighbours.index[i * k + j]; other >= 0) sets.unite(i, std::size_t(other));
  std::vector<int> label(n, -1), piece_of_root(n, -1);
  int pieces = 0;
  for (std::size_t i = 0; i < n; ++i) {
    int& piece = piece_of_root[sets.find(i)];
    if (piece < 0) piece = pieces++;
    label[i] = piece;
  }
  return label;
}

std::vector<std::vector<Vec3>> points_by_piece(const std::vector<Vec3>& points, const std::vector<int>& piece) {
  if (piece.size() != points.size()) throw AlgorithmError("points by piece: one piece label per point is needed");
  if (!piece.empty() && *std::min_element(piece.begin(), piece.end()) < 0)
    throw AlgorithmError("points by piece: a piece label is negative");
  const int count = piece.empty() ? 0 : 1 + *std::max_element(piece.begin(), piece.end());
  std::vector<std::vector<Vec3>> out(static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < points.size(); ++i) out[std::size_t(piece[i])].push_back(points[i]);
  return out;
}

}  // namespace dtsl
