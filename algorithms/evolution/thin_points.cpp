#include "algorithms/evolution/thin_points.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "framework/core/error.hpp"

namespace dtsl {

std::vector<Vec3> thin_points(const std::vector<Vec3>& points, std::size_t max_points, double cell) {
  const std::size_t n = points.size();
  if (max_points == 0 || n <= max_points) return points;
  if (!(cell > 0.0) || !std::isfinite(cell)) throw AlgorithmError("thin_points: the cell side must be positive");
  // Cell key of each point (21 bits per axis: a grid of 2^21 cells per axis covers any frame we use).
  std::vector<std::uint64_t> key(n);
  for (std::size_t k = 0; k < n; ++k) {
    std::uint64_t code = 0;
    for (int a = 0; a < 3; ++a) {
      const double c = std::floor(points[k][a] / cell) + double(1 << 20);
      code = code << 21 | std::uint64_t(std::clamp(c, 0.0, double((1 << 21) - 1)));
    }
    key[k] = code;
  }
  // Rank of each point within its cell, in input order; the cap is the largest c with sum min(count, c)
  // <= max_points, found by bisection over the cells' counts.
  std::unordered_map<std::uint64_t, std::uint32_t> count;
  count.reserve(n / 4 + 16);
  std::vector<std::uint32_t> rank(n);
  for (std::size_t k = 0; k < n; ++k) rank[k] = count[key[k]]++;
  std::vector<std::uint32_t> counts;
  counts.reserve(count.size());
  for (const auto& [cell_key, c] : count) counts.push_back(c);
  const auto kept_with = [&](std::uint32_t cap) {
    std::size_t total = 0;
    for (std::uint32_t c : counts) total += std::min(c, cap);
    return total;
  };
  std::uint32_t lo = 1, hi = *std::max_element(counts.begin(), counts.end());
  while (lo < hi) {  // largest cap in [1, hi] keeping <= max_points (1 if even that is too many)
    const std::uint32_t mid = lo + (hi - lo + 1) / 2;
    if (kept_with(mid) <= max_points) lo = mid;
    else hi = mid - 1;
  }
  std::vector<Vec3> kept;
  kept.reserve(kept_with(lo));
  for (std::size_t k = 0; k < n; ++k)
    if (rank[k] < lo) kept.push_back(points[k]);
  return kept;
}

}  // namespace dtsl
