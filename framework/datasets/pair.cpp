// `pair`: two equal objects (spheres, tori or rounded boxes) side by side along x with a gap between
// them, the case where a level set merges close objects: 2 components, genus 0 (spheres, boxes) or 2
// (tori). Each object is meshed on its own (implicit_mesher.cpp), so both are there whatever the gap.
//
// The gap is a fraction of one object's size s (its extent along x). The pair is built 2 long, so
// s = 2 / (2 + gap) and the gap in the [-1,1] frame is 2 gap / (2 + gap). In point spacings it depends
// on the sampling: with N points on a total area A (frame units), the mean spacing is about sqrt(A / N);
// e.g. two spheres, gap 0.1, 8000 points: gap 0.095, spacing 0.027, so about 3.5 spacings.
#include <cmath>

#include "framework/core/error.hpp"
#include "framework/datasets/dataset.hpp"
#include "framework/datasets/internal.hpp"
#include "framework/datasets/signed_distance.hpp"

namespace dtsl::dataset_detail {

namespace {

struct PairOptions final : Options {
  std::string object = "sphere";
  double gap = 0.1;
  double edge_length = 0.03;

  void visit(FieldVisitor& v) override {
    v.field("object", object,
            "sphere; torus (axis z, minor radius 0.3 of the major, tori side by side in one plane: genus 2 "
            "in all); or box (a cube, edges rounded by a tenth of its side, faces parallel across the gap)");
    v.field("gap", gap,
            "distance between the two surfaces along x as a fraction of one object's size; in the [-1,1] "
            "frame it is 2 gap / (2 + gap)");
    v.field("edge_length", edge_length, "target edge length of the ground-truth mesh (finer where it curves)");
  }
  void check() const override {
    check_one_of("object", object, {"sphere", "torus", "box"});
    check_range("gap", gap, 0.001, 2.0);
    // The objects are about 1 across and the torus's tube about 0.11 thick: 0.05 keeps 7 edges around it.
    check_range("edge_length", edge_length, 0.003, 0.05);
  }
};

/// One object of size `s` (its x extent) centred at `c`.
ImplicitSurface object_surface(const std::string& type, const Vec3& c, double s) {
  ImplicitSurface o;
  const double margin = 0.1 * s;
  o.box.extend(c - Vec3::Constant(0.5 * s + margin));
  o.box.extend(c + Vec3::Constant(0.5 * s + margin));
  if (type == "sphere") {
    o.f = [c, s](const Vec3& p) { return sdf::sphere(p, c, 0.5 * s); };
  } else if (type == "torus") {
    const double R = 0.5 * s / 1.3, r = 0.3 * R;  // R + r = s / 2
    o.f = [c, R, r](const Vec3& p) { return sdf::torus(p, c, R, r); };
    o.genus = 1;
  } else {
    o.f = [c, s](const Vec3& p) { return sdf::rounded_box(p, c, Vec3::Constant(0.5 * s), 0.1 * s); };
  }
  return o;
}

class Pair final : public ShapeSource {
 public:
  Options& options() override { return o_; }
  ShapeData load() override {
    const double s = 2.0 / (2.0 + o_.gap);
    const double cx = 0.5 * s * (1.0 + o_.gap);
    TriangleMesh m;
    for (const double sign : {-1.0, 1.0})
      append(m, mesh_implicit_surface(object_surface(o_.object, Vec3(sign * cx, 0.0, 0.0), s), o_.edge_length,
                                      "shape 'pair'"));
    ShapeData d;
    d.mesh = std::move(m);
    d.exact = true;
    return d;
  }

 private:
  PairOptions o_;
};

}  // namespace

void register_pair_shape() {
  shape_sources().add("pair", "two equal spheres, tori or rounded cubes with a gap along x (2 components)",
                      [] { return std::make_unique<Pair>(); });
}

}  // namespace dtsl::dataset_detail
