// Moving a level set onto a refined T-mesh (the final refinement and the coarse-to-fine evolution,
// DESIGN.md §1): control points whose knot vectors did not change keep their coefficient (f is
// unchanged where only they are active), the new or changed ones take the old f at their Greville
// point (quasi-interpolation, O(h^2) in the old cell size h): f changes only where knots changed.
#pragma once

#include "algorithms/tspline/tspline.hpp"

namespace dtsl {

/// The strongest 2:1 balance `tree` satisfies: refining with it keeps the T-mesh's kind.
Balance balance_of(const Octree& tree);

/// `old` on the T-mesh `refined` (which must refine old's T-mesh over the same domain).
TSpline transfer_level_set(const TSpline& old, Octree refined);

}  // namespace dtsl
