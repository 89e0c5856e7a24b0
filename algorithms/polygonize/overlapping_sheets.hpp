// A mesh that covers part of its surface twice: two vertices within a fraction of the step of each other,
// facing the same way, yet far apart along the mesh. Marching triangulation's fronts only see each other
// (Hartmann's distance check), not the finished mesh, so a front that crossed a part thinner than the step
// can grow over finished triangles unseen; the march with halved steps (marching_triangulation.cpp) checks
// its component with this before it is kept.
#pragma once

#include <optional>

#include "framework/core/types.hpp"

namespace dtsl {

/// A vertex of `mesh` (with vertex normals) that has another within `radius` whose normal is within 60
/// degrees of its own and that is more than `max_hops` edges away from it; nullopt if there is none.
std::optional<Vec3> overlapping_sheets(const TriangleMesh& mesh, double radius, int max_hops);

}  // namespace dtsl
