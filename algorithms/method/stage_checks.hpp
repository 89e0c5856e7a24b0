// Every stage of the method checks its mesh before handing it on, so that a diverged step never reaches
// the output as a mesh with exit status 0 (ours; the paper assumes its stages converge).
//
// The bounds, in the frame of the data (the points the pipeline was given):
// - every coordinate finite;
// - every vertex inside the data's bounding box grown on every side by kBoxMarginFraction of its longest
//   side. The T-mesh's domain reaches an eighth of the longest side past the box (0.25 in the paper's
//   [-1,1]^3 frame), so the zero set of any level set lies within it; displacement (paper §3) moves
//   vertices toward data inside the box, and hole fairing interpolates between displaced vertices, so a
//   vertex twice as far out as the domain's edge can only come from a diverged step;
// - for a stage that moves the vertices of the stage before it (D-Map, paper §3; B-Evl, paper §4), no
//   vertex moved farther than kMaxMoveFraction of the box's diagonal: a displacement is a distance to
//   nearby data, a bilateral step a fraction of the filter width; a fifth of the object's size is
//   neither.
//
// Repair, where the method says how: a D-Map or B-Evl vertex out of bounds goes back to where the
// previous stage had it (paper §3 displaces a vertex by the distance to its data; where that distance
// is not meaningful, the undisplaced level-set vertex is the method's own estimate). A stage that also
// remeshes (B-Evl removes degenerate triangles, so its vertices no longer match) cannot be repaired
// vertex by vertex: its output is replaced by the previous stage's mesh, as if the stage had not run.
// The previous stage's mesh passed these checks, so the repaired mesh does too. A stage that creates
// its mesh (MT: the zero set) has nothing to fall back on: its violation is an AlgorithmError naming
// the stage.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "framework/core/types.hpp"

namespace dtsl {

constexpr double kBoxMarginFraction = 0.25;
constexpr double kMaxMoveFraction = 0.2;

/// The region every stage's vertices must stay in: the data's box grown by kBoxMarginFraction of its
/// longest side.
struct StageBounds {
  BoundingBox box;         ///< the grown box
  double max_move = 0.0;   ///< kMaxMoveFraction of the data box's diagonal
};

/// Bounds from the data points; throws AlgorithmError for an empty set.
StageBounds stage_bounds(const std::vector<Vec3>& points);

/// What check_stage_mesh found.
struct StageCheck {
  std::size_t non_finite = 0;      ///< vertices with a NaN or infinite coordinate
  std::size_t outside = 0;         ///< vertices outside the bounds' box
  std::size_t moved_too_far = 0;   ///< vertices farther than max_move from their previous position
  std::size_t repaired = 0;        ///< vertices put back to their previous position
  bool replaced = false;           ///< the whole output replaced by the previous stage's mesh
  double max_move = 0.0;           ///< the largest finite move (0 without a previous mesh)
  double max_outside = 0.0;        ///< the largest distance outside the box
  int first_bad_vertex = -1;

  bool ok() const { return non_finite + outside + moved_too_far == 0; }
  nlohmann::json to_json() const;
};

/// Checks `mesh` of stage `stage`. With `previous` (the mesh the stage moved, same vertex count), moves
/// are checked and, when `repair` is true, every vertex out of bounds is put back to its previous
/// position. Throws AlgorithmError naming the stage, the first bad vertex and the bound when a
/// violation remains. Returns what was found (and repaired).
StageCheck check_stage_mesh(const std::string& stage, TriangleMesh& mesh, const StageBounds& bounds,
                            const TriangleMesh* previous = nullptr, bool repair = false);

/// For a stage that moves the mesh `previous` (D-Map, B-Evl): repaired vertex by vertex when the vertex
/// counts agree; otherwise, on a violation, `mesh` becomes `previous` (StageCheck::replaced). Never
/// throws for a violation.
StageCheck check_moving_stage(const std::string& stage, TriangleMesh& mesh, const StageBounds& bounds,
                              const TriangleMesh& previous);

}  // namespace dtsl
