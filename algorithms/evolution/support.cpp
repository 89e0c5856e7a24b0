#include "algorithms/evolution/support.hpp"

#include <algorithm>


namespace dtsl {

namespace {

/// Steps a ray may take, of h0 / 2 each: 200 spacings, past the object's far side for any sampling of
/// at least a few hundred points.
constexpr int kMaxRaySteps = 400;

}  // namespace

SupportData::SupportData(const DataDistance& distance, const std::vector<Vec3>& points)
    : data(&distance), spacing(distance.local_spacing(kSpacingNeighbours)) {
  std::vector<double> sorted = spacing;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  floor = 0.1 * sorted[sorted.size() / 2];
  const BoundingBox b = bounding_box(points);
  const double grow = (b.max - b.min).maxCoeff();
  box.min = b.min - Vec3::Constant(grow);
  box.max = b.max + Vec3::Constant(grow);
}

bool spans_empty_space(const TSpline& f, const SupportData& support, const Vec3& x, const Vec3& normal,
                       const NearestData& nearest) {
  const double h0 = support.spacing_at(nearest.index);
  if (nearest.distance <= h0) return false;  // on the data
  const Vec3 inward = -normal;
  // Steps of h0 / 2: the inside slab behind a membrane is as thick as the part the hole goes through,
  // which is sampled, so at least a spacing or two thick, and a data point within h of the ray's line
  // is within h of one of its steps' points give or take a quarter spacing.
  Vec3 p = x;
  bool entered = false;  // the ray starts on the zero set: first get strictly inside
  for (int step = 0; step < kMaxRaySteps; ++step) {
    const NearestData n = support.data->nearest(p);
    const double h = support.spacing_at(n.index);
    if (n.distance <= h) return false;  // met data: the membrane covers a real inside
    const double value = f.evaluate(p);
    if (value < 0.0) entered = true;
    else if (entered) return true;  // left the inside with no data on the way: empty space
    p += 0.5 * h0 * inward;
    if ((p.array() < support.box.min.array()).any() || (p.array() > support.box.max.array()).any()) return false;
  }
  return false;
}

}  // namespace dtsl
