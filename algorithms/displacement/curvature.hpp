// Principal curvatures of an implicit surface from grad f and the Hessian, and the flip check of the
// displaced mesh (paper §3.2: "the allowed displacement can be bounded with the help of the principal
// curvature radii ... computed from the implicit T-spline function"; where |d(v)| comes close to a
// radius, check the displaced triangles for flips).
#pragma once

#include <vector>

#include "framework/core/implicit.hpp"
#include "framework/core/types.hpp"

namespace dtsl {

struct PrincipalCurvatures {
  double k1 = 0.0, k2 = 0.0;  ///< |k1| >= |k2|; positive where the surface bends away from the normal (convex)
  bool valid = false;         ///< false where grad f vanishes or a value is not finite
  /// The smaller principal curvature radius 1/max|k| (infinity on a plane).
  double min_radius() const;
};

/// The shape operator of {f = c} at x: P H P / |grad f| with P = I - n n^T, n = grad f / |grad f|;
/// its two eigenvalues in the tangent plane are the principal curvatures (sphere of radius r: 1/r).
PrincipalCurvatures principal_curvatures(const Vec3& gradient, const Mat3& hessian);
PrincipalCurvatures principal_curvatures(const ImplicitFunction& f, const Vec3& x);

/// Faces whose normal reverses between `before` and `after` (same connectivity): n_before . n_after <= 0,
/// or a face that became degenerate. Only faces in `candidates` are tested (all faces if null).
std::vector<int> flipped_faces(const TriangleMesh& before, const std::vector<Vec3>& after_vertices,
                               const std::vector<int>* candidates = nullptr);

}  // namespace dtsl
