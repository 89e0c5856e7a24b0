// `geodesic`: v = -(grad d . n + lambda d kappa) (DESIGN.md §1): the gradient flow of the surface
// integral of d, i.e. geodesic active contours / the Zhao–Osher–Fedkiw model (the paper's refs [9] and
// [57]). Far from the data grad d . n is about 1, so the surface moves inward at unit speed; on the
// data grad d . n jumps from +1 (just outside the samples) to -1 (just inside), so the surface
// settles there but jitters by about one time step around it (DESIGN.md §1's lesson): the evolution's
// stopping rule on the data distance ends it. At a thin part's rim (curvature radius r) between samples
// spaced s, d kappa ~ s / r exceeds 1 once the part is thinner than its sampling: uncapped, the
// curvature term then outweighs the data's pull and erodes the part from its rim (the bunny's ears);
// `max_smoothing` caps it below 1 (ours; configs/ablation_velocity.yaml's dtsl_uncapped).
#include "algorithms/evolution/velocities/velocities.hpp"

#include <algorithm>

namespace dtsl {

namespace {

struct GeodesicVelocityOptions final : Options {
  double lambda = 1.0;
  double max_smoothing = 0.8;

  void visit(FieldVisitor& v) override {
    v.field("lambda", lambda,
            "weight of the curvature term: v = -(grad d . n + lambda d kappa); the d factor makes it "
            "vanish on the data");
    v.field("max_smoothing", max_smoothing,
            "cap on |lambda d kappa| (ours): below 1 the data's pull (|grad d . n| up to 1) outweighs the "
            "curvature term, so thin parts sampled more sparsely than they are thick (the bunny's ears) are "
            "not eroded; 1e9: uncapped");
  }
  void check() const override {
    check_range("lambda", lambda, 0.0, 100.0);
    check_range("max_smoothing", max_smoothing, 0.0, 1e9);
  }
};

class GeodesicVelocity final : public VelocityWith<GeodesicVelocityOptions, GeodesicVelocity> {
 public:
  double speed(const VelocitySample& s) const override {
    const double smoothing = std::clamp(options_.lambda * s.distance * s.curvature, -options_.max_smoothing,
                                        options_.max_smoothing);
    return -(s.distance_gradient.dot(s.normal) + smoothing);
  }
};

}  // namespace

void add_geodesic_velocity(Registry<Velocity>& registry) {
  registry.add("geodesic", "v = -(grad d . n + lambda d kappa): geodesic active contours (Zhao-Osher-Fedkiw)",
               [] { return std::make_unique<GeodesicVelocity>(); });
}

}  // namespace dtsl
