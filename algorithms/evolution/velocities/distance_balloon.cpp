// `distance_balloon` (ours, docs/design.md §1 asks for a third velocity that reaches into concavities):
//
//     v = -d (grad d . n + beta) - lambda d kappa ,   0 <= beta < 1 .
//
// Why this form (docs/design.md §1's two lessons):
//  - It vanishes on the data (every term has the factor d), so the surface comes to rest there
//    instead of jittering like `geodesic` or shrinking on like `distance`.
//  - It is fast far away: facing the data from outside, grad d . n is about 1 and v = -(1 + beta) d,
//    proportional to the distance, as fast as the CFL step allows.
//  - It is the flow of the integral of d^2/2 (v = -d grad d . n) plus a balloon force -beta d. The
//    d^2 flow alone stalls where the surface spans a concavity: there the nearest samples lie to the
//    side, grad d is tangential and grad d . n is about 0. The balloon term keeps pushing inward at
//    beta d there, so the surface reaches into the concavity (and opens the hole of a torus).
//  - It is self-correcting: where the surface has passed the data, grad d . n is about -1 and
//    v = (1 - beta) d > 0 pushes it back out (beta < 1). Between sparse samples the surface sags
//    until grad d . n = -beta: by about beta s / 2 for a sample spacing s (0.1 s at beta = 0.2), and
//    less where the coarse T-mesh cannot bend that finely.
//  - The curvature term -lambda d kappa (as in `geodesic`, scaled by d) smooths on the way in and
//    fills holes in the data with a smooth cap, and also vanishes on the data.
// Its rate near the data is 1 + beta (v ~ -(1 + beta) d), so an explicit Euler step is monotone for
// dt <= 1 / (1 + beta): EvolutionOptions::max_time_step caps dt accordingly.
#include "algorithms/evolution/velocities/velocities.hpp"

#include <algorithm>

namespace dtsl {

namespace {

struct DistanceBalloonOptions final : Options {
  double beta = 0.2;
  double lambda = 0.01;
  double open_gap = 0.0;

  void visit(FieldVisitor& v) override {
    v.field("beta", beta,
            "balloon weight in [0, 1): v = -d (grad d . n + beta) - lambda d kappa; pushes into concavities "
            "where grad d . n ~ 0, and the surface sags about beta x half the sample spacing between samples");
    v.field("lambda", lambda, "weight of the curvature term (frame units per unit curvature), scaled by d");
    v.field("open_gap", open_gap,
            "where the zero set spans empty space (support.hpp) farther than this many local spacings from "
            "the data, move inward at the far-field speed (1 + beta) d instead (ours); 0: never");
  }
  void check() const override {
    check_range("beta", beta, 0.0, 0.95);
    check_range("lambda", lambda, 0.0, 10.0);
    check_range("open_gap", open_gap, 0.0, 1e3);
  }
};

class DistanceBalloonVelocity final : public VelocityWith<DistanceBalloonOptions, DistanceBalloonVelocity> {
 public:
  double speed(const VelocitySample& s) const override {
    const double v = -s.distance * (s.distance_gradient.dot(s.normal) + options_.beta + options_.lambda * s.curvature);
    // Spanning empty space (support.hpp): the far-field speed, as if facing data.
    return s.unsupported && s.distance > options_.open_gap * s.spacing ? std::min(v, -(1.0 + options_.beta) * s.distance)
                                                                          : v;
  }
  bool wants_support() const override { return options_.open_gap > 0.0; }
};

}  // namespace

void add_distance_balloon_velocity(Registry<Velocity>& registry) {
  registry.add("distance_balloon",
               "v = -d (grad d . n + beta) - lambda d kappa: fast far away, at rest on the data, reaches "
               "into concavities (ours)",
               [] { return std::make_unique<DistanceBalloonVelocity>(); });
}

}  // namespace dtsl
