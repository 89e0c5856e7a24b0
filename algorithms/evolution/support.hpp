// Whether the zero set at a point is held by data or spans empty space (ours; the paper's §2.1 lets
// the data-driven velocity [9] decide topology, and that velocity stalls on membranes).
//
// A shrinking level set wraps the data from outside. Where it must pass through a hole of the object
// (a plate's through-hole, a lattice's window, the gap between two objects, the space between an arm
// and the body), it first spans the hole with a membrane. On a membrane the nearest data lie to the
// side, so grad d . n is about 0 and a flat membrane has no curvature: the paper's velocity
// v = -(grad d . n + lambda d kappa) is about 0 there, and the membrane stays (the rocker arm of the
// paper's Fig. 1 came out genus 0). A hole in the data of a closed surface (a scanner's hole, a plane
// cut) is spanned the same way and must stay closed: there the membrane covers the object's inside.
//
// The data tell the two apart along the inward normal. Behind a membrane over a through-hole lies a
// slab of the inside region that holds no data: the ray from the membrane inward leaves the inside
// (f > 0 again, at the membrane on the far side of the hole) without coming near a data point. Behind a
// membrane over a hole in the data lies the object's inside, and the ray meets data (the far wall)
// before it leaves. So a zero-set point is *unsupported* when it is farther than the local spacing h
// from the data and its inward ray leaves the inside region without coming within h of a data point,
// where h is the sampling spacing of the nearest data (the mean distance to its kSpacingNeighbours
// nearest): scale-free, so sparse parts of a non-uniform sampling tolerate proportionally larger gaps
// and stay connected. A data gap a ray slips through is wider than about two spacings on both sides of
// a part, which is a hole.
#pragma once

#include <vector>

#include "algorithms/evolution/data_distance.hpp"
#include "algorithms/tspline/tspline.hpp"

namespace dtsl {

/// The neighbours whose mean distance is a data point's local spacing h.
constexpr int kSpacingNeighbours = 8;

/// What support tests need of the data, computed once per evolution.
struct SupportData {
  const DataDistance* data = nullptr;
  std::vector<double> spacing;  ///< h per data point (DataDistance::local_spacing(kSpacingNeighbours))
  double floor = 0.0;           ///< lower bound of h (a fraction of the median; repeated points read 0)
  BoundingBox box;              ///< where rays end undecided (the data's box grown by its longest side)

  SupportData(const DataDistance& distance, const std::vector<Vec3>& points);
  /// h at data point `index`.
  double spacing_at(int index) const { return std::max(spacing[index], floor); }
};

/// Whether the zero set of `f` at `x` (outward normal `normal`, nearest data point `nearest`) spans
/// empty space: farther than h from the data, and the ray x - t normal leaves the inside region
/// (f > 0) before it comes within h of a data point. A ray that leaves the box, or does not decide
/// within its step budget, counts as supported (the membrane stays: the safe side). Thread-safe.
bool spans_empty_space(const TSpline& f, const SupportData& support, const Vec3& x, const Vec3& normal,
                       const NearestData& nearest);

}  // namespace dtsl
