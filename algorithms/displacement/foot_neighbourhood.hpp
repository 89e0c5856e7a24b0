// The data's foot points around a base vertex, and the Gaussian taps of a filter over them (paper §3.2:
// "the displacement d(v) of a vertex is the Gaussian-weighted mean of the d_k of the nearby data").
// The neighbourhood is a Euclidean ball around v over the foot points (all on f = 0), which for widths
// well below the curvature radii is the geodesic one the paper's per-triangle lists I_i describe; a
// normal test keeps the other side of a thin part out. Every filter plugin (displacement_filter.hpp)
// builds its taps from these.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "algorithms/displacement/projection.hpp"
#include "algorithms/displacement/vertex_grid.hpp"
#include "framework/core/types.hpp"

namespace dtsl {

/// One vertex's filter: (data point index, weight) pairs; the vertex's value is the weighted sum of a
/// per-point value (d_k, or a residual).
using FilterTaps = std::vector<std::pair<int, double>>;
/// A vertex's feet within a support: (data point index, squared distance to the vertex).
using FootReach = std::vector<std::pair<int, double>>;

/// Foot points farther than this x the width from a vertex are left out: the Gaussian is ~1% there.
constexpr double kFilterSupport = 3.0;

/// The valid foot points of a projection, indexed for ball queries at a ladder of filter widths.
class FootNeighbourhoods {
 public:
  /// `widths`: increasing, at least one. `normals`: grad f / |grad f| at the base vertices. Throws
  /// AlgorithmError when no point was projected.
  FootNeighbourhoods(const TriangleMesh& base, const ProjectionResult& projection, const std::vector<Vec3>& normals,
                     std::vector<double> widths);

  const std::vector<double>& widths() const { return widths_; }
  /// More than one width: the taps of width j are a prefix of a reach (grouped by width).
  bool widened() const { return widths_.size() > 1; }
  /// The widths up to this one are gathered from all feet; wider ones from every stride()-th foot.
  std::size_t near() const { return near_; }
  std::size_t stride() const { return far_grid_ ? stride_ : 1; }

  /// v's feet within the support of widths()[upto] whose normal is within 90 degrees of v's.
  void gather(long v, FootReach& reach, std::size_t upto) const;
  /// The feet of `reach` within kFilterSupport x `width`, Gaussian-weighted and normalised to sum 1;
  /// false where they fail the hole test (no foot, or weights summing below 0.05).
  bool gaussian_taps(const FootReach& reach, double width, FilterTaps& out) const;
  /// The hole test alone at `width` (any width, not only the ladder's): true where the feet of `reach`
  /// within its support weigh enough.
  bool supported(const FootReach& reach, double width) const;
  /// The tangential offset of the taps' weighted centroid from v, / width: ~0 with feet all round,
  /// ~0.8 on a straight rim of even data (the hole rim test, hole_rim.hpp).
  double one_sidedness(long v, const FilterTaps& taps, double width) const;

 private:
  const TriangleMesh& base_;
  const ProjectionResult& projection_;
  const std::vector<Vec3>& normals_;
  std::vector<double> widths_, support2_;
  std::size_t near_ = 0, stride_ = 1;
  std::vector<Vec3> feet_, far_feet_;
  std::vector<int> foot_id_, far_foot_id_;
  PointGrid foot_grid_;
  std::unique_ptr<PointGrid> far_grid_;
};

}  // namespace dtsl
