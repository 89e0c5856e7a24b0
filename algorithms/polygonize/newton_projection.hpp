// Newton projection of a point onto the zero set of an implicit function: the paper's §3.1 step 3.2,
//     q <- q - f(q) grad f(q) / |grad f(q)|^2 ,
// repeated until the step is small. The polygonizers use it to put new vertices on f = 0 and to find
// the data points' foot points (the seeds of §2.2); Phase 2 (displacement mapping) uses it for the
// foot points q_k and their signed displacements.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "framework/core/implicit.hpp"

namespace dtsl {

struct NewtonOptions {
  /// Converged when the next step |f| / |grad f| (a first-order distance to f = 0) is below this,
  /// in frame units. The returned point then satisfies |f| / |grad f| < tolerance.
  double tolerance = 1e-10;
  /// Iteration cap; a projection that has not converged by then is reported as failed.
  int max_iterations = 50;
  /// Longest single step (frame units). Clamping keeps the iteration from jumping across to another
  /// sheet when it starts far from the surface or where |grad f| is small; infinity = the paper's step.
  double max_step = std::numeric_limits<double>::infinity();
  /// |grad f| below this counts as a critical point: the step is undefined and the projection fails.
  double min_gradient = 1e-12;

  /// Throws ConfigError naming `prefix` + the field for a value out of range.
  void check(const std::string& prefix = "newton_") const;
};

enum class NewtonStatus { converged, max_iterations, zero_gradient, not_finite };
const char* to_string(NewtonStatus status);

struct NewtonProjection {
  Vec3 point = Vec3::Zero();     ///< the last iterate (on f = 0 to tolerance if converged)
  Vec3 gradient = Vec3::Zero();  ///< grad f at `point`
  double value = 0.0;            ///< f at `point`
  int iterations = 0;            ///< Newton steps taken
  NewtonStatus status = NewtonStatus::max_iterations;
  bool converged() const { return status == NewtonStatus::converged; }
  /// grad f / |grad f| at the point: the outward unit normal.
  Vec3 normal() const { return gradient.normalized(); }
};

/// Projects `start` onto f = 0. Never throws for numerical trouble: the status says what happened.
NewtonProjection newton_project(const ImplicitFunction& f, const Vec3& start, const NewtonOptions& options = {});

/// Projects every point (OpenMP-parallel); result i belongs to points[i].
std::vector<NewtonProjection> newton_project_all(const ImplicitFunction& f, const std::vector<Vec3>& points,
                                                 const NewtonOptions& options = {});

}  // namespace dtsl
