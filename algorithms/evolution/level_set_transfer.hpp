// Moving a level set onto a refined T-mesh (the final refinement and the coarse-to-fine evolution,
// docs/design.md §1). Control points whose knot vectors did not change keep their coefficient (f is
// unchanged where only they are active); the new or changed ones take the old f at their Greville point
// (quasi-interpolation, O(h^2) in the old cell size h). A refined T-spline space need not contain the
// coarse one, so the transfer is not exact: it moves the zero set by part of the data's distance to it,
// which the fit after it undoes. f changes only where knots changed. (A least-squares transfer was
// measured and removed: docs/method.md, "Refinement".)
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "algorithms/tspline/tspline.hpp"

namespace dtsl {

/// The strongest 2:1 balance `tree` satisfies: refining with it keeps the T-mesh's kind.
Balance balance_of(const Octree& tree);

/// What a transfer did (the final refinement's record).
struct TransferReport {
  int changed = 0;           ///< control points whose knots changed (quasi-interpolated)
  std::vector<char> changed_flags;  ///< per control point of the refined basis: 1 where it changed
  double seconds = 0.0;
};
nlohmann::json to_json(const TransferReport& r);

/// `old` on the T-mesh `refined`. Pre-condition: `refined` refines old's T-mesh over the same domain
/// (refine_octree of it); not checked.
TSpline transfer_level_set(const TSpline& old, Octree refined, TransferReport* report = nullptr);

}  // namespace dtsl
