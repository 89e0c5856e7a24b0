// The initial level set of the evolution (docs/design.md §1): f_0 = signed distance to a sphere enclosing
// every data point — centre at the data's bounding-box centre, radius radius_factor (1.1) x the
// largest distance from that centre to a point — put into coefficients by quasi-interpolation
// (c_i = f_0 at the Greville point of B_i).
//
// Clipping (ours): in the [-1,1]^3 frame that sphere reaches past the T-mesh's domain whenever the data
// fill the corners of their box (radius up to 1.1 sqrt 3 = 1.9 > 1 + margin = 1.25). The zero set is
// then cut off by the domain's faces, the inside region touches the boundary, and the evolution first
// has to peel it off the faces — slowly, and leaving pockets of f < 0 stuck on the boundary. So the
// sphere is intersected with the data's bounding box grown by box_margin on every side, its edges and
// corners rounded with radius box_rounding (f_0 = max(sphere distance, rounded-box distance), still a
// function whose zero set encloses every point, inside the domain as long as box_margin < margin).
// The rounding matters: quasi-interpolated on coarse cells, a sharp box corner is cut off by about
// half a cell and would leave data at the box's corners outside f_0 < 0 (tested). A point at the data
// box's corner is sqrt(3) box_margin - 0.73 r inside a corner rounded with radius r: most (r =
// box_margin, where the rounding sphere is centred on that point) for the least rounding that still
// quasi-interpolates well. For data
// that already fit in the sphere inside the box, nothing changes. box_margin <= 0 disables the
// clipping (the docs/design.md sphere alone). Limitation: where the T-mesh near the box's faces is coarser
// than about 2 (margin - box_margin) (cells of 0.31 at level 3 against a gap of 0.15), the
// quasi-interpolant blurs the box across the domain's faces and the initial zero set may still touch
// them there; the evolution peels it off as it moves in.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "algorithms/tspline/tspline.hpp"

namespace dtsl {

struct EnclosingSurface {
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;
  bool clipped = false;  ///< intersect the sphere with `box`
  BoundingBox box;
  double rounding = 0.0;  ///< radius of the box's rounded edges and corners
  /// Signed distance (an exact one for the sphere alone; max of the two for the intersection, exact
  /// outside both and a lower bound of the true distance elsewhere).
  double operator()(const Vec3& x) const;
};

/// The sphere of docs/design.md §1, clipped to the data's box grown by box_margin when box_margin > 0. The
/// clip box is at least 2 min_half_extent wide along every axis (centred on the data), so flat data
/// (a plate, a plane) still start inside a slab the T-mesh can represent: a slab thinner than a
/// cell quasi-interpolates to a function without a zero set. AlgorithmError for no points or
/// radius_factor < 1 (the sphere would not enclose the data).
EnclosingSurface enclosing_surface(const std::vector<Vec3>& points, double radius_factor, double box_margin,
                                   double min_half_extent = 0.0, double box_rounding = -1.0);
/// box_rounding < 0 above means the default: box_margin.

/// The quasi-interpolant of the surface's signed distance on `basis`.
TSpline initial_level_set(std::shared_ptr<const TSplineBasis> basis, const EnclosingSurface& surface);

/// The initial level set of the stage for `points` on `basis`: enclosing_surface() with a clip box at
/// least one coarsest leaf of the T-mesh thick on each side of the data's centre, quasi-interpolated,
/// then lowered by a constant (f reproduces constants: every coefficient minus the same amount) as far
/// as needed for every data point to lie at least a quarter of the finest leaf side inside: on coarse
/// cells the quasi-interpolant rounds the box's corners off by a fraction of a cell, and data in those
/// corners would otherwise start outside (tested).
TSpline initial_level_set(std::shared_ptr<const TSplineBasis> basis, const std::vector<Vec3>& points,
                          double radius_factor, double box_margin);

/// The quasi-interpolant of any signed distance whose negative side holds the data (the data's wrap,
/// data_wrap.hpp), lowered like the sphere's above until every data point lies at least a quarter of
/// the finest leaf side inside.
TSpline initial_level_set(std::shared_ptr<const TSplineBasis> basis, const std::vector<Vec3>& points,
                          const std::function<double(const Vec3&)>& signed_distance);

}  // namespace dtsl
