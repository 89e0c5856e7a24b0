// Output of the level-set stage: the level set (T-mesh and coefficients) saved and
// re-loadable, and the T-mesh as line geometry for figures (the paper's Fig. 1a and 3a).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "algorithms/tspline/tspline.hpp"

namespace dtsl {

/// Writes the T-mesh (domain, max_depth, the leaves) and the coefficients to a text file, atomically.
/// Numbers are written with 17 significant digits, so a loaded spline evaluates bit-identically.
/// Format (one record a line, '#' starts a comment line):
///   dtsl-tspline 1
///   domain <min x> <min y> <min z> <side>
///   max_depth <D>
///   leaves <L>          then L lines: <level> <origin x> <origin y> <origin z>  (finest-level units)
///   coefficients <n>    then n lines: <c_i>  (control points in control_vertices() order)
///   end
void save_tspline(const std::string& path, const TSpline& spline);

/// Reads a file written by save_tspline. FileError naming the file and the line for anything
/// malformed: wrong header or version, bad numbers, leaves that overlap or leave gaps, a coefficient
/// count that does not match the T-mesh's control points, a truncated file.
TSpline load_tspline(const std::string& path);

/// The edges of the leaf cells as line segments (world coordinates), each lattice edge once.
std::vector<std::array<Vec3, 2>> tmesh_edges(const Octree& octree);

/// Writes the T-mesh edges as a Wavefront .obj of 'v' and 'l' records.
void write_tmesh_obj(const std::string& path, const Octree& octree);

}  // namespace dtsl
