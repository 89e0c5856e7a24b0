// Ball queries over the foot points at a ladder of widths, and the Gaussian taps (paper §3.2).
#include "algorithms/displacement/foot_neighbourhood.hpp"

#include <algorithm>
#include <cmath>

#include "framework/core/error.hpp"

namespace dtsl {

namespace {

// Feet whose normal makes more than this angle with the vertex normal are ignored: on a thin part the
// other side's data lies within the support but belongs elsewhere.
const double kCosMaxNormalAngle = std::cos(90.0 * M_PI / 180.0);
// A vertex whose Gaussian weights sum to less than this (all its feet beyond ~2.4 widths) is a hole
// vertex: normalising tiny weights would extrapolate one far point's d.
constexpr double kMinWeight = 0.05;
// Noisy data with more feet than this x the vertices: the widths beyond near() take every k-th foot, so
// a filter 4 edges wide does not gather thousands of feet per vertex at 1M points, where a few hundred
// already put the noise's share far below the noise (docs/performance.md).
constexpr double kMaxFeetPerVertex = 8.0;

}  // namespace

FootNeighbourhoods::FootNeighbourhoods(const TriangleMesh& base, const ProjectionResult& projection,
                                       const std::vector<Vec3>& normals, std::vector<double> widths)
    : base_(base), projection_(projection), normals_(normals), widths_(std::move(widths)) {
  for (double w : widths_) support2_.push_back(std::pow(kFilterSupport * w, 2));
  std::size_t valid = 0;
  for (std::size_t k = 0; k < projection.foot_points.size(); ++k) valid += projection.valid[k] ? 1 : 0;
  if (valid == 0) throw AlgorithmError("displacement: no data point could be projected onto f = 0");
  for (std::size_t k = 0; k < projection.foot_points.size(); ++k)
    if (projection.valid[k]) feet_.push_back(projection.foot_points[k]), foot_id_.push_back(static_cast<int>(k));
  // Cells about half the query radius: a widened filter's ball (up to 8x the base radius) would
  // otherwise visit thousands of empty cells per vertex. Most vertices stop widening early, so their
  // feet are first gathered for the first few widths only (`near`), from a finer grid.
  near_ = std::min<std::size_t>(2, widths_.size() - 1);
  foot_grid_ = PointGrid(feet_, 0.5 * kFilterSupport * widths_[near_] * (widened() ? 1.0 : 2.0));
  const double per_vertex_cap = kMaxFeetPerVertex * static_cast<double>(base.vertices.size());
  stride_ = static_cast<double>(valid) > per_vertex_cap
                ? static_cast<std::size_t>(std::ceil(static_cast<double>(valid) / per_vertex_cap))
                : 1;
  if (near_ + 1 < widths_.size()) {  // in point order: deterministic
    for (std::size_t i = 0; i < feet_.size(); i += stride_)
      far_feet_.push_back(feet_[i]), far_foot_id_.push_back(foot_id_[i]);
    far_grid_ = std::make_unique<PointGrid>(far_feet_, 0.5 * kFilterSupport * widths_.back());
  }
}

void FootNeighbourhoods::gather(long v, FootReach& reach, std::size_t upto) const {
  reach.clear();
  const bool far = upto > near_;
  const PointGrid& grid = far ? *far_grid_ : foot_grid_;
  const std::vector<int>& ids = far ? far_foot_id_ : foot_id_;
  grid.for_each_within(base_.vertices[v], kFilterSupport * widths_[upto], [&](int i, double d2) {
    const int k = ids[i];
    if (projection_.foot_normals[k].dot(normals_[v]) < kCosMaxNormalAngle) return;
    reach.emplace_back(k, d2);
  });
  if (!widened()) return;
  // Grouped by the narrowest width whose support holds them (a counting sort, stable, so the order
  // stays the grid's: deterministic), so that each width's taps are a prefix.
  std::vector<int> group(reach.size());
  std::vector<std::size_t> start(widths_.size() + 1, 0);
  for (std::size_t t = 0; t < reach.size(); ++t) {
    const std::size_t j = static_cast<std::size_t>(
        std::lower_bound(support2_.begin(), support2_.end(), reach[t].second) - support2_.begin());
    group[t] = static_cast<int>(std::min(j, widths_.size() - 1));
    ++start[group[t] + 1];
  }
  for (std::size_t j = 1; j < start.size(); ++j) start[j] += start[j - 1];
  FootReach sorted(reach.size());
  for (std::size_t t = 0; t < reach.size(); ++t) sorted[start[group[t]]++] = reach[t];
  reach.swap(sorted);
}

bool FootNeighbourhoods::gaussian_taps(const FootReach& reach, double width, FilterTaps& out) const {
  const double inv2s2 = 1.0 / (2.0 * width * width), keep2 = std::pow(kFilterSupport * width, 2);
  out.clear();
  double wsum = 0.0;
  for (const auto& [k, d2] : reach) {
    if (d2 > keep2) {
      if (widened()) break;  // grouped by width: the rest lie beyond this one
      continue;
    }
    const double w = std::exp(-d2 * inv2s2);
    wsum += w;
    out.emplace_back(k, w);
  }
  if (out.empty() || !(wsum > 0) || wsum < kMinWeight) return false;
  // A fixed summation order: the same d whatever the threads (widened: the width-group, then grid-cell
  // order of `reach` already is).
  if (!widened()) std::sort(out.begin(), out.end());
  for (auto& tap : out) tap.second /= wsum;
  return true;
}

bool FootNeighbourhoods::supported(const FootReach& reach, double width) const {
  const double inv2s2 = 1.0 / (2.0 * width * width), keep2 = std::pow(kFilterSupport * width, 2);
  double wsum = 0.0;
  for (const auto& [k, d2] : reach)
    if (d2 <= keep2 && (wsum += std::exp(-d2 * inv2s2)) >= kMinWeight) return true;
  return false;
}

double FootNeighbourhoods::one_sidedness(long v, const FilterTaps& taps, double width) const {
  Vec3 centroid = Vec3::Zero();
  for (const auto& [k, w] : taps) centroid += w * (projection_.foot_points[k] - base_.vertices[v]);
  centroid -= centroid.dot(normals_[v]) * normals_[v];
  return centroid.norm() / width;
}

}  // namespace dtsl
