#include "algorithms/evolution/initial_level_set.hpp"

#include <algorithm>
#include <limits>
#include <utility>

#include "framework/core/error.hpp"

namespace dtsl {

double EnclosingSurface::operator()(const Vec3& x) const {
  const double sphere = (x - centre).norm() - radius;
  if (!clipped) return sphere;
  // Signed distance to the rounded box: the box shrunk by the rounding radius, offset by it.
  const Vec3 inner = (0.5 * box.extent() - Vec3::Constant(rounding)).cwiseMax(0.0);
  const Vec3 q = (x - box.center()).cwiseAbs() - inner;
  const double box_distance = q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0) - rounding;
  return std::max(sphere, box_distance);
}

EnclosingSurface enclosing_surface(const std::vector<Vec3>& points, double radius_factor, double box_margin,
                                   double min_half_extent, double box_rounding) {
  if (points.empty()) throw AlgorithmError("initial level set: no data points");
  if (!(radius_factor >= 1.0))
    throw AlgorithmError("initial level set: radius factor must be >= 1 to enclose the data");
  EnclosingSurface s;
  const BoundingBox box = bounding_box(points);
  s.centre = box.center();
  double largest = 0.0;
  for (const Vec3& p : points) largest = std::max(largest, (p - s.centre).norm());
  s.radius = radius_factor * largest;
  if (box_margin > 0.0) {
    s.clipped = true;
    s.box.min = box.min - Vec3::Constant(box_margin);
    s.box.max = box.max + Vec3::Constant(box_margin);
    for (int a = 0; a < 3; ++a) {
      const double half = std::max(0.5 * (s.box.max[a] - s.box.min[a]), min_half_extent);
      s.box.min[a] = s.centre[a] - half;
      s.box.max[a] = s.centre[a] + half;
    }
    s.rounding = box_rounding >= 0.0 ? box_rounding : box_margin;
  }
  return s;
}

TSpline initial_level_set(std::shared_ptr<const TSplineBasis> basis, const EnclosingSurface& surface) {
  return quasi_interpolant(std::move(basis), [&surface](const Vec3& x) { return surface(x); });
}

namespace {

std::pair<double, double> coarsest_and_finest_leaf(const TSplineBasis& basis) {
  double coarsest = 0.0, finest = std::numeric_limits<double>::infinity();
  const Octree& tree = basis.octree();
  for (int l = 0; l < tree.leaf_count(); ++l) {
    coarsest = std::max(coarsest, tree.leaf_side(l));
    finest = std::min(finest, tree.leaf_side(l));
  }
  return {coarsest, finest};
}

// f reproduces constants: lowering every coefficient lowers f by the same amount.
void lower_below_data(TSpline& f, const std::vector<Vec3>& points, double finest) {
  double highest = -std::numeric_limits<double>::infinity();
  for (const Vec3& p : points) highest = std::max(highest, f.evaluate(p));
  const double lower = highest + 0.25 * finest;
  if (lower > 0.0)
    for (double& c : f.coefficients()) c -= lower;
}

}  // namespace

TSpline initial_level_set(std::shared_ptr<const TSplineBasis> basis, const std::vector<Vec3>& points,
                          double radius_factor, double box_margin) {
  const auto [coarsest, finest] = coarsest_and_finest_leaf(*basis);
  const EnclosingSurface surface = enclosing_surface(points, radius_factor, box_margin, coarsest);
  TSpline f = initial_level_set(std::move(basis), surface);
  lower_below_data(f, points, finest);
  return f;
}

TSpline initial_level_set(std::shared_ptr<const TSplineBasis> basis, const std::vector<Vec3>& points,
                          const std::function<double(const Vec3&)>& signed_distance) {
  if (points.empty()) throw AlgorithmError("initial level set: no data points");
  const double finest = coarsest_and_finest_leaf(*basis).second;
  TSpline f = quasi_interpolant(std::move(basis), signed_distance);
  // Lowered locally: every coefficient active at a data point that is not a quarter of the finest leaf
  // inside drops by that point's shortfall (f = sum c_i R_i with R_i >= 0 summing to 1, so the point then
  // is), leaving the holes and gaps elsewhere as the distance put them.
  const double margin = 0.25 * finest;
  std::vector<double> drop(f.coefficients().size(), 0.0);
  ActiveBasis active;
  for (const Vec3& p : points) {
    const double shortfall = f.evaluate(p) + margin;
    if (!(shortfall > 0.0)) continue;
    f.basis().active(p, active);
    for (int i : active.index) drop[i] = std::max(drop[i], shortfall);
  }
  for (std::size_t i = 0; i < drop.size(); ++i) f.coefficients()[i] -= drop[i];
  return f;
}

}  // namespace dtsl
