// `geodesic`: v = -(grad d . n + lambda d kappa) (docs/design.md §1): the gradient flow of the surface
// integral of d, i.e. geodesic active contours / the Zhao–Osher–Fedkiw model (the paper's refs [9] and
// [57]). Far from the data grad d . n is about 1, so the surface moves inward at unit speed; on the
// data grad d . n jumps from +1 (just outside the samples) to -1 (just inside), so the surface
// settles there but jitters by about one time step around it (docs/design.md §1's lesson): the evolution's
// stopping rule on the data distance ends it. At a thin part's rim (curvature radius r) between samples
// spaced s, d kappa ~ s / r exceeds 1 once the part is thinner than its sampling: uncapped, the
// curvature term then outweighs the data's pull and erodes the part from its rim (the bunny's ears);
// `max_smoothing` caps it below 1 (ours; configs/ablation_velocity.yaml's dtsl_uncapped).
//
// Where the zero set spans empty space (support.hpp: a membrane over a through-hole, a bridge across
// the gap between two objects), grad d . n and kappa are about 0 and the flow above stalls; there the
// surface moves inward at the far-field speed 1 instead (ours), until the membrane opens or meets
// data — where it lies farther than `open_gap` local spacings from the data. Through-holes and gaps
// between objects narrower than twice that stay closed, and so do gaps in the data across a thin part
// (a scanner's hole through an ear leaves its tip as a separate cluster: support.hpp). `paper` is the flow of the paper's §2.1 as published (its refs [9], [55]):
// uncapped, and membranes stay.
#include "algorithms/evolution/velocities/velocities.hpp"

#include <algorithm>

namespace dtsl {

namespace {

struct GeodesicVelocityOptions final : Options {
  double lambda = 1.0;
  double max_smoothing = 0.8;
  double open_gap = 0.0;

  void visit(FieldVisitor& v) override {
    v.field("lambda", lambda,
            "weight of the curvature term: v = -(grad d . n + lambda d kappa); the d factor makes it "
            "vanish on the data");
    v.field("max_smoothing", max_smoothing,
            "cap on |lambda d kappa| (ours): below 1 the data's pull (|grad d . n| up to 1) outweighs the "
            "curvature term, so thin parts sampled more sparsely than they are thick (the bunny's ears) are "
            "not eroded; 1e9: uncapped");
    v.field("open_gap", open_gap,
            "where the zero set spans empty space (a membrane over a through-hole or across a gap between "
            "objects: support.hpp) farther than this many local spacings from the data, move inward at the "
            "far-field speed 1 instead of stalling (ours); 0: never, membranes stay as with the paper's velocity "
            "(the default: on the topology suite's dev half open_gap 1 changes which inputs get the truth's "
            "topology, not how many, and cuts a thin part where the data have a hole across it)");
  }
  void check() const override {
    check_range("lambda", lambda, 0.0, 100.0);
    check_range("max_smoothing", max_smoothing, 0.0, 1e9);
    check_range("open_gap", open_gap, 0.0, 1e3);
  }
};

class GeodesicVelocity final : public VelocityWith<GeodesicVelocityOptions, GeodesicVelocity> {
 public:
  double speed(const VelocitySample& s) const override {
    const double smoothing = std::clamp(options_.lambda * s.distance * s.curvature, -options_.max_smoothing,
                                        options_.max_smoothing);
    const double v = -(s.distance_gradient.dot(s.normal) + smoothing);
    return s.unsupported && s.distance > options_.open_gap * s.spacing ? std::min(v, -1.0) : v;
  }
  bool wants_support() const override { return options_.open_gap > 0.0; }
};

/// The paper's velocity (§2.1 with its refs [9], [55]): geodesic active contours on the data distance,
/// v = -(grad d . n + lambda d kappa), uncapped; membranes over holes stay.
struct PaperVelocityOptions final : Options {
  double lambda = 1.0;
  void visit(FieldVisitor& v) override {
    v.field("lambda", lambda, "weight of the curvature term: v = -(grad d . n + lambda d kappa)");
  }
  void check() const override { check_range("lambda", lambda, 0.0, 100.0); }
};

class PaperVelocity final : public VelocityWith<PaperVelocityOptions, PaperVelocity> {
 public:
  double speed(const VelocitySample& s) const override {
    return -(s.distance_gradient.dot(s.normal) + options_.lambda * s.distance * s.curvature);
  }
};

}  // namespace

void add_geodesic_velocity(Registry<Velocity>& registry) {
  registry.add("geodesic", "v = -(grad d . n + lambda d kappa): geodesic active contours (Zhao-Osher-Fedkiw)",
               [] { return std::make_unique<GeodesicVelocity>(); });
  registry.add("paper", "the paper's velocity (§2.1, refs [9], [55]): v = -(grad d . n + lambda d kappa), uncapped",
               [] { return std::make_unique<PaperVelocity>(); });
}

}  // namespace dtsl
