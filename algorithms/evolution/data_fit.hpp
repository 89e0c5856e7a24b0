// How far the data are from the level set, as the evolution's stopping rule and history read it
// (docs/design.md §1: "stop when ... the mean data-to-level-set distance stops decreasing").
//
// First-order distance |f(p)| / |grad f(p)| per data point: one gradient evaluation, no iteration.
// With the distance-field constraint holding (|grad f| ~ 1 near the zero set) it is the Newton step
// length, within O(distance^2 x curvature) of the true distance near the surface; far from the zero
// set it is only an estimate (where f still carries the initial sphere's distance it overestimates).
// Tests measure the exact Newton foot-point distance instead.
#pragma once

#include <vector>

#include "framework/core/implicit.hpp"

namespace dtsl {

struct DataFit {
  double mean = 0.0;  ///< mean over the points of |f(p)| / |grad f(p)|
  double max = 0.0;   ///< largest of them
  int critical = 0;   ///< points where grad f vanishes (counted with distance |f|; none on a healthy level set)
};

/// OpenMP-parallel; AlgorithmError for no points.
DataFit data_fit(const ImplicitFunction& f, const std::vector<Vec3>& points);

}  // namespace dtsl
