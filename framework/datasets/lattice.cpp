// `lattice`: a wireframe of round bars along the edges of an nx x ny x nz grid of cubic cells, its joints
// rounded by fillets: windows of about a cell through which a level set must not grow membranes, and
// many handles close together. The solid is a thickened graph (nodes: the grid's corners, edges: the
// bars between neighbours), so its genus is the graph's cycle rank E - V + 1 with
//   V = (nx+1)(ny+1)(nz+1),  E = nx(ny+1)(nz+1) + (nx+1)ny(nz+1) + (nx+1)(ny+1)nz.
// A cubic frame [1,1,1] (12 bars) has genus 5; a flat 3x3 grid [3,3,0] genus 9; [2,2,2] genus 28.
// Built with its longest side 2 (bar axes), so its lengths are in the [-1,1] frame.
#include <cmath>

#include "framework/core/error.hpp"
#include "framework/datasets/dataset.hpp"
#include "framework/datasets/internal.hpp"
#include "framework/datasets/signed_distance.hpp"

namespace dtsl::dataset_detail {

namespace {

struct LatticeOptions final : Options {
  std::vector<double> cells{1.0, 1.0, 1.0};
  double bar_radius = 0.1;
  double blend = 0.5;
  double edge_length = 0.045;

  void visit(FieldVisitor& v) override {
    v.field("cells", cells,
            "cells along x, y, z (integers 0-6; at most one 0, which makes a flat grid). Genus E - V + 1: "
            "[1,1,1] 5, [2,1,1] 9, [3,3,0] 9, [2,2,2] 28");
    v.field("bar_radius", bar_radius, "bar radius as a fraction of the cell size");
    v.field("blend", blend, "width of the fillets at the joints as a fraction of the bar radius");
    v.field("edge_length", edge_length, "target edge length of the ground-truth mesh (finer where it curves)");
  }

  int n(int axis) const { return static_cast<int>(cells.at(axis)); }
  double cell() const { return 2.0 / std::max({n(0), n(1), n(2)}); }
  int genus() const {
    const int nx = n(0), ny = n(1), nz = n(2);
    const int V = (nx + 1) * (ny + 1) * (nz + 1);
    const int E = nx * (ny + 1) * (nz + 1) + (nx + 1) * ny * (nz + 1) + (nx + 1) * (ny + 1) * nz;
    return E - V + 1;
  }

  void check() const override {
    require(cells.size() == 3, "cells", "must have 3 entries, got " + std::to_string(cells.size()));
    int zeros = 0;
    for (const double c : cells) {
      require(c == std::floor(c) && c >= 0.0 && c <= 6.0, "cells",
              "each entry must be an integer in [0, 6], got " + format_number(c));
      zeros += c == 0.0 ? 1 : 0;
    }
    require(zeros <= 1, "cells", "at most one entry may be 0 (a flat grid); more leaves no window");
    // Windows of at least 0.4 cell between the bars' surfaces.
    check_range("bar_radius", bar_radius, 0.02, 0.3);
    check_range("blend", blend, 0.1, 1.0);  // no crease at the joints: the surface stays smooth
    check_positive("edge_length", edge_length);
    const double r = bar_radius * cell();
    require(edge_length <= 0.5 * r * (1.0 + 1e-9), "edge_length",
            "must be at most half the bar radius (" + format_number(0.5 * r) + ") so the bars are resolved, got " +
                format_number(edge_length));
    const double bars = cells[0] * (cells[1] + 1) * (cells[2] + 1) + (cells[0] + 1) * cells[1] * (cells[2] + 1) +
                        (cells[0] + 1) * (cells[1] + 1) * cells[2];
    const double vertices = 1.2 * bars * cell() * 2.0 * M_PI * r / (edge_length * edge_length);
    require(vertices <= 2e6, "edge_length",
            "too small for this lattice: about " + format_number(std::round(vertices)) +
                " vertices (at most 2000000), got " + format_number(edge_length));
  }
};

/// The bars along `axis` near p: those through the two nearest grid lines in each of the other two
/// directions (a farther bar is more than a blend width farther, so it changes nothing).
double bars_along(const Vec3& p, int axis, const int n[3], double cell, double radius, double blend, double value) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  if (n[axis] == 0) return value;  // a flat grid has no bar across its plane
  const double length = n[axis] * cell;
  auto candidates = [&](int w, int out[2]) {
    const int i = static_cast<int>(std::floor(p[w] / cell));
    out[0] = std::clamp(i, 0, n[w]);
    out[1] = std::clamp(i + 1, 0, n[w]);
  };
  int cu[2], cv[2];
  candidates(u, cu);
  candidates(v, cv);
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      if ((a == 1 && cu[1] == cu[0]) || (b == 1 && cv[1] == cv[0])) continue;  // clamped twice: same bar
      Vec3 start = Vec3::Zero();
      start[u] = cu[a] * cell;
      start[v] = cv[b] * cell;
      Vec3 end = start;
      end[axis] = length;
      value = sdf::smooth_union(value, sdf::capsule(p, start, end, radius), blend);
    }
  return value;
}

class Lattice final : public ShapeSource {
 public:
  Options& options() override { return o_; }
  ShapeData load() override {
    const int n[3] = {o_.n(0), o_.n(1), o_.n(2)};
    const double cell = o_.cell(), r = o_.bar_radius * cell, blend = o_.blend * r;
    ImplicitSurface s;
    s.f = [=](const Vec3& q) {
      // Centred: the grid spans [0, n cell] on each axis before the shift.
      const Vec3 p = q + 0.5 * cell * Vec3(n[0], n[1], n[2]);
      double v = 1e30;
      for (int axis = 0; axis < 3; ++axis) v = bars_along(p, axis, n, cell, r, blend, v);
      return v;
    };
    const Vec3 half = 0.5 * cell * Vec3(n[0], n[1], n[2]) + Vec3::Constant(r + 2.0 * o_.edge_length);
    s.box.extend(-half);
    s.box.extend(half);
    s.components = 1;
    s.genus = o_.genus();
    ShapeData d;
    d.mesh = mesh_implicit_surface(s, o_.edge_length, "shape 'lattice'");
    d.exact = true;
    return d;
  }

 private:
  LatticeOptions o_;
};

}  // namespace

void register_lattice_shape() {
  shape_sources().add("lattice", "wireframe of round bars along a grid of cells (genus = bars - joints + 1)",
                      [] { return std::make_unique<Lattice>(); });
}

}  // namespace dtsl::dataset_detail
