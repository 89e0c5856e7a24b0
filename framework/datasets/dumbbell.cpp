// `dumbbell`: two equal balls joined by a thin cylindrical neck, the junctions rounded by fillets; genus
// 0, one component. The neck is what a level set pinches off (two components) or a reconstruction
// thickens. Built 2 long along x, so its lengths are in the [-1,1] frame: ball radius 2 / (4 + neck_length).
#include <cmath>

#include "framework/core/error.hpp"
#include "framework/datasets/dataset.hpp"
#include "framework/datasets/internal.hpp"
#include "framework/datasets/signed_distance.hpp"

namespace dtsl::dataset_detail {

namespace {

struct DumbbellOptions final : Options {
  double neck_radius = 0.15;
  double neck_length = 1.0;
  double blend = 0.1;
  double edge_length = 0.02;

  void visit(FieldVisitor& v) override {
    v.field("neck_radius", neck_radius, "radius of the neck as a fraction of the balls' radius");
    v.field("neck_length", neck_length, "distance between the two balls' surfaces as a fraction of their radius");
    v.field("blend", blend, "width of the fillets where the neck meets the balls, a fraction of the balls' radius");
    v.field("edge_length", edge_length, "target edge length of the ground-truth mesh (finer where it curves)");
  }
  double ball_radius() const { return 2.0 / (4.0 + neck_length); }
  void check() const override {
    check_range("neck_radius", neck_radius, 0.02, 0.7);
    check_range("neck_length", neck_length, 0.05, 4.0);
    check_range("blend", blend, 0.01, 0.5);  // no crease: the surface stays smooth
    check_positive("edge_length", edge_length);
    const double r = neck_radius * ball_radius();
    require(edge_length <= 0.5 * r * (1.0 + 1e-9), "edge_length",
            "must be at most half the neck's radius (" + format_number(0.5 * r) + ") so the neck is resolved, got " +
                format_number(edge_length));
    const double area = 2.0 * 4.0 * M_PI * ball_radius() * ball_radius();
    const double vertices = 1.2 * area / (edge_length * edge_length);
    require(vertices <= 2e6, "edge_length",
            "too small: about " + format_number(std::round(vertices)) + " vertices (at most 2000000), got " +
                format_number(edge_length));
  }
};

class Dumbbell final : public ShapeSource {
 public:
  Options& options() override { return o_; }
  ShapeData load() override {
    const double R = o_.ball_radius(), r = o_.neck_radius * R, blend = o_.blend * R;
    const double cx = R * (1.0 + 0.5 * o_.neck_length);  // ball centres at +-cx; the shape spans [-1, 1] in x
    ImplicitSurface s;
    s.f = [=](const Vec3& p) {
      const double balls = std::min(sdf::sphere(p, Vec3(-cx, 0, 0), R), sdf::sphere(p, Vec3(cx, 0, 0), R));
      return sdf::smooth_union(balls, sdf::capsule(p, Vec3(-cx, 0, 0), Vec3(cx, 0, 0), r), blend);
    };
    const double m = 2.0 * o_.edge_length;
    s.box.extend(Vec3(-cx - R - m, -R - m, -R - m));
    s.box.extend(Vec3(cx + R + m, R + m, R + m));
    ShapeData d;
    d.mesh = mesh_implicit_surface(s, o_.edge_length, "shape 'dumbbell'");
    d.exact = true;
    return d;
  }

 private:
  DumbbellOptions o_;
};

}  // namespace

void register_dumbbell_shape() {
  shape_sources().add("dumbbell", "two balls joined by a thin neck with fillets (genus 0)",
                      [] { return std::make_unique<Dumbbell>(); });
}

}  // namespace dtsl::dataset_detail
