// `distance`: v = -d(x) - lambda kappa (docs/design.md §1, "shrink-wrap by distance").
//
// The surface moves inward at the distance to the nearest data point, smoothed by mean-curvature flow.
// It is fast far from the data and slows as it approaches, but v never changes sign: the surface does
// not come to rest on the data, it only slows down (-lambda kappa keeps shrinking convex parts) — the
// evolution's stopping rule (the mean data-to-level-set distance stops decreasing) ends it, and the
// evolution keeps the iterate closest to the data.
#include "algorithms/evolution/velocities/velocities.hpp"

namespace dtsl {

namespace {

struct DistanceVelocityOptions final : Options {
  double lambda = 0.002;

  void visit(FieldVisitor& v) override {
    v.field("lambda", lambda,
            "weight of the curvature term (frame units^2 per time): v = -d - lambda kappa; larger smooths "
            "more and shrinks convex parts more");
  }
  void check() const override { check_range("lambda", lambda, 0.0, 1.0); }
};

class DistanceVelocity final : public VelocityWith<DistanceVelocityOptions, DistanceVelocity> {
 public:
  double speed(const VelocitySample& s) const override { return -s.distance - options_.lambda * s.curvature; }
};

}  // namespace

void add_distance_velocity(Registry<Velocity>& registry) {
  registry.add("distance", "v = -d - lambda kappa: shrink-wrap at the distance to the data, curvature-smoothed",
               [] { return std::make_unique<DistanceVelocity>(); });
}

}  // namespace dtsl
