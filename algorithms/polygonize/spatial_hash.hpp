// A uniform hash grid of integer ids at points: the distance checks of the marching triangulation
// (every front point against every other front point within ~delta, Hartmann 1998 §3) and the seed
// coverage test (foot point against mesh vertices) run in O(1) per query instead of O(front size).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "framework/core/types.hpp"

namespace dtsl {

class SpatialHash {
 public:
  /// `cell` should be about the query radius: a query then visits 27 cells.
  explicit SpatialHash(double cell) : inv_cell_(1.0 / cell) {}

  void insert(int id, const Vec3& p) { cells_[key(p)].push_back(id); }

  /// Removes one occurrence of `id` inserted at `p` (same point as given to insert).
  void remove(int id, const Vec3& p) {
    auto it = cells_.find(key(p));
    if (it == cells_.end()) return;
    auto& v = it->second;
    auto pos = std::find(v.begin(), v.end(), id);
    if (pos == v.end()) return;
    *pos = v.back();
    v.pop_back();
    if (v.empty()) cells_.erase(it);
  }

  /// Calls visit(id) for every id in the cells overlapping the ball (p, radius); the caller filters
  /// by exact distance (ids farther than radius may be visited).
  template <class Visit>
  void for_each_near(const Vec3& p, double radius, Visit&& visit) const {
    const Eigen::Vector3i lo = cell_of(p - Vec3::Constant(radius));
    const Eigen::Vector3i hi = cell_of(p + Vec3::Constant(radius));
    for (int i = lo.x(); i <= hi.x(); ++i)
      for (int j = lo.y(); j <= hi.y(); ++j)
        for (int k = lo.z(); k <= hi.z(); ++k) {
          auto it = cells_.find(pack(i, j, k));
          if (it == cells_.end()) continue;
          for (int id : it->second) visit(id);
        }
  }

  void clear() { cells_.clear(); }

 private:
  Eigen::Vector3i cell_of(const Vec3& p) const {
    return Eigen::Vector3i(static_cast<int>(std::floor(p.x() * inv_cell_)),
                           static_cast<int>(std::floor(p.y() * inv_cell_)),
                           static_cast<int>(std::floor(p.z() * inv_cell_)));
  }
  static std::uint64_t pack(int i, int j, int k) {
    // 21 bits per axis: +-1M cells, far beyond any frame-sized grid.
    const auto u = [](int x) { return static_cast<std::uint64_t>(x + (1 << 20)) & 0x1FFFFFu; };
    return (u(i) << 42) | (u(j) << 21) | u(k);
  }
  std::uint64_t key(const Vec3& p) const {
    const Eigen::Vector3i c = cell_of(p);
    return pack(c.x(), c.y(), c.z());
  }

  double inv_cell_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

}  // namespace dtsl
