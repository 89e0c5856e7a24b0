// The T-mesh as a picture (the paper's Fig. 1a, "the data points and the T-mesh"): the edges of the
// octree leaves that hold given samples, e.g. the data points and the vertices of the level set's
// triangulation (the leaves the zero set crosses). All leaves would bury the data under the coarse
// cells of empty space in front of it; these show what the figure is for: where the T-spline is fine
// (dense data) and where coarse (sparse data, holes).
#pragma once

#include <array>
#include <vector>

#include "algorithms/tspline/octree.hpp"

namespace dtsl {

/// The edges of the leaves of `octree` holding at least one of `samples` (located as Octree::locate
/// does: points outside the domain count for the leaf they are clamped onto), world coordinates, each
/// lattice edge once (those of tmesh_edges(), filtered). Every edge of such a leaf is included, and so is
/// an edge of a finer neighbour lying on its face (a T-junction of the T-mesh).
std::vector<std::array<Vec3, 2>> tmesh_edges_around(const Octree& octree, const std::vector<Vec3>& samples);

}  // namespace dtsl
