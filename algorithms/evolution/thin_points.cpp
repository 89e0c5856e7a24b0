#include "algorithms/evolution/thin_points.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <tuple>

#include "framework/core/error.hpp"

namespace dtsl {

namespace {

/// Cell of x in a grid of side `cell` anchored at the origin, 21 bits per axis (2^21 cells per axis
/// cover any frame we use), z-minor: ordering by it groups each cell's points together.
std::uint64_t cell_key(const Vec3& x, double cell) {
  std::uint64_t code = 0;
  for (int a = 0; a < 3; ++a) {
    const double c = std::floor(x[a] / cell) + double(1 << 20);
    code = code << 21 | std::uint64_t(std::clamp(c, 0.0, double((1 << 21) - 1)));
  }
  return code;
}

bool coordinates_less(const Vec3& a, const Vec3& b) {
  return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z());
}

}  // namespace

std::vector<Vec3> thin_points(const std::vector<Vec3>& points, std::size_t max_points, double cell) {
  const std::size_t n = points.size();
  if (max_points == 0 || n <= max_points) return points;
  if (!(cell > 0.0) || !std::isfinite(cell)) throw AlgorithmError("thin_points: the cell side must be positive");
  std::vector<std::uint64_t> key(n);
  for (std::size_t k = 0; k < n; ++k) key[k] = cell_key(points[k], cell);
  // The points cell by cell, each cell's by their coordinates: nothing below depends on the input order.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return key[a] != key[b] ? key[a] < key[b] : coordinates_less(points[a], points[b]);
  });
  std::vector<std::size_t> group_begin;  // cell g holds order[group_begin[g], group_begin[g + 1])
  for (std::size_t k = 0; k < n; ++k)
    if (k == 0 || key[order[k]] != key[order[k - 1]]) group_begin.push_back(k);
  group_begin.push_back(n);
  const std::size_t groups = group_begin.size() - 1;

  // The cap is the largest c with sum min(count, c) <= max_points, found by bisection over the counts.
  const auto kept_with = [&](std::size_t cap) {
    std::size_t total = 0;
    for (std::size_t g = 0; g < groups; ++g) total += std::min(group_begin[g + 1] - group_begin[g], cap);
    return total;
  };
  std::size_t lo = 1, hi = 1;
  for (std::size_t g = 0; g < groups; ++g) hi = std::max(hi, group_begin[g + 1] - group_begin[g]);
  while (lo < hi) {  // largest cap in [1, hi] keeping <= max_points (1 if even that is too many)
    const std::size_t mid = lo + (hi - lo + 1) / 2;
    if (kept_with(mid) <= max_points) lo = mid;
    else hi = mid - 1;
  }
  const std::size_t cap = lo;

  // A dense cell keeps `cap` points spread over it: the cell split into m^3 sub-cells, m = ceil(sqrt(cap))
  // (a surface through the cell meets about m^2 of them), and the points taken by their rank within
  // their sub-cell (first the one nearest each sub-cell's centre, then the next nearest, ...), ties by
  // the distance to the sub-cell's centre. The first points in input order instead would be one scan
  // line's in a scanner's output, leaving the rest of the cell bare.
  const int m = int(std::ceil(std::sqrt(double(cap)) - 1e-9));
  const double sub = cell / double(m);
  struct Candidate {
    int sub_cell, rank = 0;
    double centre_distance;
    std::size_t point;
  };
  std::vector<Vec3> kept;
  kept.reserve(kept_with(cap));
  std::vector<Candidate> candidates;
  for (std::size_t g = 0; g < groups; ++g) {
    const std::size_t begin = group_begin[g], end = group_begin[g + 1];
    if (end - begin <= cap) {
      for (std::size_t k = begin; k < end; ++k) kept.push_back(points[order[k]]);
      continue;
    }
    const Vec3& first = points[order[begin]];
    Vec3 corner;
    for (int a = 0; a < 3; ++a) corner[a] = std::floor(first[a] / cell) * cell;
    candidates.clear();
    for (std::size_t k = begin; k < end; ++k) {
      const Vec3& x = points[order[k]];
      std::array<int, 3> s{};
      Vec3 centre;
      for (int a = 0; a < 3; ++a) {
        s[std::size_t(a)] = std::clamp(int(std::floor((x[a] - corner[a]) / sub)), 0, m - 1);
        centre[a] = corner[a] + (s[std::size_t(a)] + 0.5) * sub;
      }
      candidates.push_back({(s[0] * m + s[1]) * m + s[2], 0, (x - centre).squaredNorm(), order[k]});
    }
    // Stable sorts over the coordinate order of the cell's points: ties keep it.
    std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
      return a.sub_cell != b.sub_cell ? a.sub_cell < b.sub_cell : a.centre_distance < b.centre_distance;
    });
    for (std::size_t k = 1; k < candidates.size(); ++k)
      if (candidates[k].sub_cell == candidates[k - 1].sub_cell) candidates[k].rank = candidates[k - 1].rank + 1;
    std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
      return a.rank != b.rank ? a.rank < b.rank : a.centre_distance < b.centre_distance;
    });
    for (std::size_t k = 0; k < cap; ++k) kept.push_back(points[candidates[k].point]);
  }
  return kept;
}

}  // namespace dtsl
