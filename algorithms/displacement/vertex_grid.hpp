// A dense uniform grid over a fixed set of points (mesh vertices or data foot points) answering the two
// queries of Phase 2 (paper §3.1 step 3.5 and §3.2): the nearest point to a query, and every point in a
// ball. Cell size ~ the mesh edge length (the marching step delta), so a nearest query visits a few
// cells and a Gaussian-support query (3 sigma) a few dozen. Measured against brute force in
// tests/displacement (same answers; see the timing test's output).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "framework/core/types.hpp"

namespace dtsl {

class PointGrid {
 public:
  PointGrid() = default;
  /// Indexes `points` (kept by pointer: they must outlive the grid and not change). `cell` > 0; the
  /// grid is capped at ~max_cells cells by enlarging the cell.
  PointGrid(const std::vector<Vec3>& points, double cell, std::size_t max_cells = 1u << 22) : points_(&points) {
    if (points.empty()) return;
    BoundingBox box = bounding_box(points);
    origin_ = box.min;
    const Vec3 ext = box.extent();
    h_ = cell > 0 ? cell : 1.0;
    for (;;) {
      for (int a = 0; a < 3; ++a) n_[a] = std::max(1, static_cast<int>(std::floor(ext[a] / h_)) + 1);
      if (static_cast<double>(n_[0]) * n_[1] * n_[2] <= static_cast<double>(max_cells)) break;
      h_ *= 1.5;
    }
    start_.assign(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2] + 1, 0);
    std::vector<int> cell_of_point(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      cell_of_point[i] = linear(cell_of(points[i]));
      ++start_[cell_of_point[i] + 1];
    }
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    ids_.resize(points.size());
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < points.size(); ++i) ids_[fill[cell_of_point[i]]++] = static_cast<int>(i);
  }

  bool empty() const { return points_ == nullptr || points_->empty(); }
  double cell() const { return h_; }

  /// Index of the point nearest to q (ties: any), -1 for an empty grid. Exact: rings of cells around
  /// q's (clamped) cell are searched until no unsearched cell can hold a closer point.
  int nearest(const Vec3& q, double* distance = nullptr) const {
    if (empty()) return -1;
    const Eigen::Vector3i c = cell_of(q);
    int best = -1;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (int r = 0;; ++r) {
      // Visit the shell of Chebyshev radius r.
      for (int i = c.x() - r; i <= c.x() + r; ++i) {
        if (i < 0 || i >= n_[0]) continue;
        for (int j = c.y() - r; j <= c.y() + r; ++j) {
          if (j < 0 || j >= n_[1]) continue;
          const bool edge_ij = std::abs(i - c.x()) == r || std::abs(j - c.y()) == r;
          for (int k = c.z() - r; k <= c.z() + r; ++k) {
            if (k < 0 || k >= n_[2]) continue;
            if (!edge_ij && std::abs(k - c.z()) != r) {  // interior of the shell: jump to its far face
              if (k < c.z() + r) k = c.z() + r - 1;
              continue;
            }
            const int l = linear(Eigen::Vector3i(i, j, k));
            for (int s = start_[l]; s < start_[l + 1]; ++s) {
              const double d2 = ((*points_)[ids_[s]] - q).squaredNorm();
              if (d2 < best_d2) best_d2 = d2, best = ids_[s];
            }
          }
        }
      }
      // Lower bound on the distance to any cell outside the searched box.
      double bound = std::numeric_limits<double>::infinity();
      for (int a = 0; a < 3; ++a) {
        if (c[a] + r + 1 < n_[a]) bound = std::min(bound, origin_[a] + (c[a] + r + 1) * h_ - q[a]);
        if (c[a] - r - 1 >= 0) bound = std::min(bound, q[a] - (origin_[a] + (c[a] - r) * h_));
      }
      if (bound == std::numeric_limits<double>::infinity() || (best >= 0 && best_d2 <= bound * bound)) break;
    }
    if (distance) *distance = std::sqrt(best_d2);
    return best;
  }

  /// Calls visit(index, squared distance) for every point within `radius` of q.
  template <class Visit>
  void for_each_within(const Vec3& q, double radius, Visit&& visit) const {
    if (empty()) return;
    const double r2 = radius * radius;
    const Eigen::Vector3i lo = cell_of(q - Vec3::Constant(radius)), hi = cell_of(q + Vec3::Constant(radius));
    for (int i = lo.x(); i <= hi.x(); ++i)
      for (int j = lo.y(); j <= hi.y(); ++j)
        for (int k = lo.z(); k <= hi.z(); ++k) {
          const int l = linear(Eigen::Vector3i(i, j, k));
          for (int s = start_[l]; s < start_[l + 1]; ++s) {
            const double d2 = ((*points_)[ids_[s]] - q).squaredNorm();
            if (d2 <= r2) visit(ids_[s], d2);
          }
        }
  }

 private:
  Eigen::Vector3i cell_of(const Vec3& p) const {  // clamped into the grid
    Eigen::Vector3i c;
    for (int a = 0; a < 3; ++a) {
      const double t = std::floor((p[a] - origin_[a]) / h_);
      c[a] = t < 0 ? 0 : (t >= n_[a] ? n_[a] - 1 : static_cast<int>(t));
    }
    return c;
  }
  int linear(const Eigen::Vector3i& c) const { return (c.x() * n_[1] + c.y()) * n_[2] + c.z(); }

  const std::vector<Vec3>* points_ = nullptr;
  Vec3 origin_ = Vec3::Zero();
  double h_ = 1.0;
  int n_[3] = {1, 1, 1};
  std::vector<int> start_, ids_;
};

}  // namespace dtsl
