// A hole's rim (DisplacementOptions::rim_offset; ours): the vertices beside a hole whose filter's feet lie
// to one side extrapolate the data across the rim, so they join the hole and its fill starts where the
// data stop. Only holes of at least min_hole_vertices connected vertices grow: on sparse data the weight
// test leaves gaps of a vertex or two, which have no rim.
#pragma once

#include <cstddef>
#include <vector>

namespace dtsl {

/// `known[v]` == 0 marks a hole vertex. A known vertex with one_sidedness[v] > rim_offset next to a
/// vertex of a hole of at least min_hole_vertices connected hole vertices joins it (known[v] = 0), ring
/// after ring up to `rings`. `neighbours[v]`: the vertices adjacent to v. Returns the vertices that
/// joined, in the order they did.
std::vector<int> grow_hole_rims(const std::vector<std::vector<int>>& neighbours, const std::vector<double>& one_sidedness,
                                double rim_offset, int rings, int min_hole_vertices, std::vector<char>& known);

}  // namespace dtsl
