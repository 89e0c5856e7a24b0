// Line geometry as Wavefront OBJ `v` and `l` records: how a run keeps the lines a stage leaves for
// figures (the T-mesh's cell edges, StageLines) and how the report reads them back. The format is that
// of write_tmesh_obj (algorithms/tspline/tspline_io.hpp), so read_line_obj reads those files too.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "framework/core/types.hpp"

namespace dtsl {

using Segment = std::array<Vec3, 2>;

/// Writes the segments, end points shared (numbered once each), atomically: a reader never sees half a
/// file. FileError naming `path` for a NaN or infinite coordinate (nothing is written) or an I/O failure.
void write_line_obj(const std::string& path, const std::vector<Segment>& segments, const std::string& comment = "");

/// The segments of an OBJ file's `l` records (a polyline `l a b c` is the segments a-b, b-c; 1-based or
/// negative indices); faces and other records are ignored. FileError naming the file and the line for
/// anything malformed (bad numbers, an index out of range, an `l` with fewer than two vertices).
std::vector<Segment> read_line_obj(const std::string& path);

}  // namespace dtsl
