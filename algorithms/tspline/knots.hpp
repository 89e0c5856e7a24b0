// Control points of the T-mesh and their local knot vectors: the 3-D form of Sederberg's T-spline rule
// (paper §2.1 and its ref. [47]; the rule itself is ours, docs/design.md §1).
#pragma once

#include <array>
#include <vector>

#include "algorithms/tspline/octree.hpp"

namespace dtsl {

/// Five knots per axis, in finest-level lattice units (exact integers; may lie outside the domain
/// where the rule extends past the boundary). knots[axis][2] is the vertex's own coordinate.
using LatticeKnots = std::array<int, 5>;
using LocalKnots = std::array<LatticeKnots, 3>;

/// The control points: every vertex of every leaf cell, hanging (T-junction) vertices included,
/// without duplicates, sorted by (z, y, x) — a deterministic order, so coefficient vectors written
/// to a file mean the same thing when read back.
std::vector<Int3> control_vertices(const Octree& octree);

/// The local knot vectors of a vertex of the T-mesh. Along each axis and each direction, a ray is cast
/// from the vertex through the leaf cells adjacent to it (up to four: the ray runs along cell edges or
/// faces, or through a cell) and the next two cell-face coordinates it meets are taken, each the
/// nearest face over all the cells adjacent to the ray. Past the domain boundary the last interval's
/// length is repeated (for a vertex on the boundary: the first interval on the other side).
LocalKnots local_knots(const Octree& octree, const Int3& vertex);

}  // namespace dtsl
