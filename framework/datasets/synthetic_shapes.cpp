// Synthetic smooth shapes with exact ground truth: fine tessellations whose vertices lie on the analytic
// surface and carry its analytic normals. Lengths are in the shape's own frame: the dataset normalises
// every shape into [-1,1]^3 before sampling, so only ratios of a shape's lengths change the data.
#include <cmath>

#include "framework/core/error.hpp"
#include "framework/datasets/dataset.hpp"
#include "framework/datasets/internal.hpp"

namespace dtsl::dataset_detail {

namespace {

void check_vec3(const char* field, const std::vector<double>& v) {
  require(v.size() == 3, field, "must have 3 entries, got " + std::to_string(v.size()));
}

// ---- sphere -----------------------------------------------------------------------------------

struct SphereOptions final : Options {
  double radius = 1.0;
  std::vector<double> centre{0.0, 0.0, 0.0};
  int subdivisions = 5;

  void visit(FieldVisitor& v) override {
    v.field("radius", radius, "sphere radius (shape frame; the shape is then normalised into [-1,1]^3)");
    v.field("centre", centre, "sphere centre [x, y, z] (shape frame)");
    v.field("subdivisions", subdivisions,
            "icosphere subdivision level: 10*4^s+2 vertices (5: 10242, the `vertices` sampler's point count)");
  }
  void check() const override {
    check_positive("radius", radius);
    check_vec3("centre", centre);
    // 8 is 655k vertices: beyond that the mesh only costs memory.
    check_range("subdivisions", subdivisions, 0, 8);
  }
};

class Sphere final : public ShapeSource {
 public:
  Options& options() override { return o_; }
  ShapeData load() override {
    ShapeData d;
    d.mesh = icosphere(to_vec3(o_.centre), o_.radius, o_.subdivisions);
    d.exact = true;
    return d;
  }

 private:
  SphereOptions o_;
};

// ---- torus ------------------------------------------------------------------------------------

struct TorusOptions final : Options {
  double R = 1.0;
  double r = 0.4;
  int major_segments = 160;
  int minor_segments = 64;

  void visit(FieldVisitor& v) override {
    v.field("R", R, "major radius: centre of the tube to the axis (z)");
    v.field("r", r, "minor radius: of the tube; r < R keeps it a ring torus (genus 1)");
    v.field("major_segments", major_segments, "vertices around the axis");
    v.field("minor_segments", minor_segments,
            "vertices around the tube (major/minor = R/r gives square cells)");
  }
  void check() const override {
    check_positive("R", R);
    check_positive("r", r);
    require(r < R, "r", "must be smaller than R (a ring torus, genus 1), got r=" + format_number(r) +
                            ", R=" + format_number(R));
    check_range("major_segments", major_segments, 3, 4096);
    check_range("minor_segments", minor_segments, 3, 4096);
  }
};

TriangleMesh torus_mesh(double R, double r, int nu, int nv) {
  TriangleMesh m;
  const double two_pi = 2.0 * M_PI;
  for (int i = 0; i < nu; ++i) {
    const double u = two_pi * i / nu;
    for (int j = 0; j < nv; ++j) {
      const double w = two_pi * j / nv;
      const Vec3 n(std::cos(w) * std::cos(u), std::cos(w) * std::sin(u), std::sin(w));
      m.vertices.push_back(Vec3(R * std::cos(u), R * std::sin(u), 0.0) + r * n);
      m.normals.push_back(n);
    }
  }
  auto id = [&](int i, int j) { return (i % nu) * nv + (j % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      // (d/du x d/dv) points outward for this parametrisation, so (i,j) -> (i+1,j) -> (i+1,j+1) is
      // counter-clockwise seen from outside.
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

class Torus final : public ShapeSource {
 public:
  Options& options() override { return o_; }
  ShapeData load() override {
    ShapeData d;
    d.mesh = torus_mesh(o_.R, o_.r, o_.major_segments, o_.minor_segments);
    d.exact = true;
    return d;
  }

 private:
  TorusOptions o_;
};

// ---- two spheres ------------------------------------------------------------------------------

struct TwoSpheresOptions final : Options {
  double radius = 1.0;
  double gap = 0.5;
  int subdivisions = 5;

  void visit(FieldVisitor& v) override {
    v.field("radius", radius, "radius of each sphere (shape frame)");
    v.field("gap", gap,
            "distance between the two surfaces along x (shape frame; after normalisation it is "
            "gap * 2 / (4 radius + gap))");
    v.field("subdivisions", subdivisions, "icosphere subdivision level of each sphere");
  }
  void check() const override {
    check_positive("radius", radius);
    check_positive("gap", gap);
    check_range("subdivisions", subdivisions, 0, 8);
  }
};

class TwoSpheres final : public ShapeSource {
 public:
  Options& options() override { return o_; }
  ShapeData load() override {
    const double cx = o_.radius + 0.5 * o_.gap;
    TriangleMesh m = icosphere(Vec3(-cx, 0.0, 0.0), o_.radius, o_.subdivisions);
    append(m, icosphere(Vec3(cx, 0.0, 0.0), o_.radius, o_.subdivisions));
    ShapeData d;
    d.mesh = std::move(m);
    d.exact = true;
    return d;
  }

 private:
  TwoSpheresOptions o_;
};

}  // namespace

void register_synthetic_shapes() {
  shape_sources().add("sphere", "icosphere with analytic normals (genus 0)",
                      [] { return std::make_unique<Sphere>(); });
  shape_sources().add("torus", "ring torus around z with analytic normals (genus 1)",
                      [] { return std::make_unique<Torus>(); });
  shape_sources().add("two_spheres", "two equal separate spheres along x (2 components)",
                      [] { return std::make_unique<TwoSpheres>(); });
}

}  // namespace dtsl::dataset_detail
