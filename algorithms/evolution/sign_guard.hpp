// No nucleation (ours): the evolution may not create new pieces of the zero set away from the moving
// front. A level-set PDE moves the zero set continuously; it never makes a bubble appear where the
// surface is not. The least-squares step can: the distance-field rows of the band pull on controls
// whose support does not reach the zero set, and where the band meets the far field that was left
// behind by the front (docs/design.md §1 fixes c' only near the surface), f develops a ridge and a valley
// that can dip through zero: spurious bubbles without this guard (docs/design.md §8).
//
// The guard uses the convex-hull property of the rational T-spline (R_i >= 0, sum R_i = 1: f(x) lies
// between the smallest and largest coefficient active at x). A control point is "at the surface" when
// some zero-set row (a velocity, data or thin-wall row, thin_walls.hpp) touches it; every other
// control point that a step changed may not change sign nor come closer to zero than min(floor_i, |c_i|
// before the step), with floor_i a fraction of its cell size. Where all active coefficients keep one sign and stay away from zero, f
// cannot vanish: the zero set can only move where it already is. Topology changes are unaffected:
// where two fronts meet (a torus opening, a neck pinching off), the controls are at the surface.
#pragma once

#include <vector>

#include "algorithms/evolution/least_squares_rows.hpp"

namespace dtsl {

/// floor_i = fraction x the side of the leaf holding the Greville point of control point i.
std::vector<double> sign_floors(const TSplineBasis& basis, double fraction);

/// Applies the guard to `after` (the coefficients after a step from `before`), for the unknowns of
/// `system` not touched by its first `surface_rows` rows. Returns how many coefficients it changed.
int guard_signs(const LeastSquaresSystem& system, int surface_rows, const std::vector<double>& floors,
                const std::vector<double>& before, std::vector<double>& after);

/// Separation (ours): the control points flagged in `held` (their Greville point lies in a gap the carving
/// opened between separate pieces of the data, data_carving.hpp) stay positive, at least min(floor_i,
/// c_i before the step), whether the front touches them or not. Across a gap of a few cells the two
/// fronts share these controls, and the least-squares step would otherwise pull them through zero and
/// grow a neck between the pieces, a topology change the data do not support. Returns how many it changed.
int hold_outside(const std::vector<char>& held, const std::vector<double>& floors, const std::vector<double>& before,
                 std::vector<double>& after);

}  // namespace dtsl
