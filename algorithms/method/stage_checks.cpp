#include "algorithms/method/stage_checks.hpp"

#include <cmath>
#include <sstream>

#include "framework/core/error.hpp"

namespace dtsl {

StageBounds stage_bounds(const std::vector<Vec3>& points) {
  if (points.empty()) throw AlgorithmError("stage bounds: no data points");
  const BoundingBox data = bounding_box(points);
  const Vec3 size = data.max - data.min;
  StageBounds b;
  const double margin = kBoxMarginFraction * size.maxCoeff();
  b.box.min = data.min - Vec3::Constant(margin);
  b.box.max = data.max + Vec3::Constant(margin);
  b.max_move = kMaxMoveFraction * size.norm();
  return b;
}

nlohmann::json StageCheck::to_json() const {
  return {{"non_finite", non_finite}, {"outside", outside},          {"moved_too_far", moved_too_far},
          {"repaired", repaired},     {"replaced", replaced},        {"max_move", max_move},
          {"max_outside", max_outside}};
}

namespace {

double distance_outside(const BoundingBox& box, const Vec3& p) {
  const Vec3 below = (box.min - p).cwiseMax(0.0), above = (p - box.max).cwiseMax(0.0);
  return (below + above).norm();
}

std::string describe(const Vec3& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

}  // namespace

StageCheck check_stage_mesh(const std::string& stage, TriangleMesh& mesh, const StageBounds& bounds,
                            const TriangleMesh* previous, bool repair) {
  if (previous && previous->vertices.size() != mesh.vertices.size())
    throw AlgorithmError("stage " + stage + ": " + std::to_string(mesh.vertices.size()) + " vertices, the mesh it moved has " +
                         std::to_string(previous->vertices.size()));
  StageCheck c;
  std::string first_problem;
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    Vec3& v = mesh.vertices[i];
    const bool finite = v.allFinite();
    const double outside = finite ? distance_outside(bounds.box, v) : 0.0;
    const double move = finite && previous ? (v - previous->vertices[i]).norm() : 0.0;
    const bool far = move > bounds.max_move;
    if (finite) {
      c.max_outside = std::max(c.max_outside, outside);
      c.max_move = std::max(c.max_move, move);
    }
    if (finite && outside == 0.0 && !far) continue;
    if (!finite) ++c.non_finite;
    if (outside > 0.0) ++c.outside;
    if (far) ++c.moved_too_far;
    if (first_problem.empty()) {
      c.first_bad_vertex = int(i);
      first_problem = "vertex " + std::to_string(i) + " at " + describe(v) +
                      (!finite ? " is not finite"
                               : outside > 0.0 ? " lies " + std::to_string(outside) +
                                                     " outside the data's box grown by a quarter of its longest side"
                                               : " moved " + std::to_string(move) + ", more than the bound " +
                                                     std::to_string(bounds.max_move) + " (a fifth of the data's diagonal)");
    }
    if (repair && previous) {
      v = previous->vertices[i];
      ++c.repaired;
    }
  }
  // Repaired vertices are back where the previous (checked) stage had them; anything else is an error.
  if (!c.ok() && !(repair && previous))
    throw AlgorithmError("stage " + stage + " diverged: " + first_problem + " (" +
                         std::to_string(c.non_finite + c.outside + c.moved_too_far) +
                         " vertices out of bounds); no mesh is written");
  return c;
}

StageCheck check_moving_stage(const std::string& stage, TriangleMesh& mesh, const StageBounds& bounds,
                              const TriangleMesh& previous) {
  if (mesh.vertices.size() == previous.vertices.size()) return check_stage_mesh(stage, mesh, bounds, &previous, true);
  try {
    return check_stage_mesh(stage, mesh, bounds);
  } catch (const AlgorithmError&) {
    StageCheck c;
    // What was wrong before the replacement, for the record.
    for (const Vec3& v : mesh.vertices) {
      if (!v.allFinite()) ++c.non_finite;
      else if (const double out = distance_outside(bounds.box, v); out > 0.0) {
        ++c.outside;
        c.max_outside = std::max(c.max_outside, out);
      }
    }
    c.replaced = true;
    mesh = previous;
    return c;
  }
}

}  // namespace dtsl
