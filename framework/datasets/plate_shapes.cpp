// Plates with round through-holes, the shapes on which a level set closes holes with membranes:
//   plate_holes: a rounded rectangular plate with 1-5 holes of given diameters in a row (genus k);
//   high_genus:  a slab with a rows x columns grid of equal holes (genus rows * columns).
// The plate is the set of points within thickness/2 of a flat rounded rectangle (a smooth slab with
// half-round rims); each hole is a cylinder taken away with its rims rounded over `rim_blend`, so the
// surface is smooth everywhere and meshed exactly by implicit_mesher.cpp. Both are built with their
// length (x) equal to 2, so their lengths are in the [-1,1] frame the dataset normalises into.
#include <cmath>
#include <numeric>

#include "framework/core/error.hpp"
#include "framework/datasets/dataset.hpp"
#include "framework/datasets/internal.hpp"
#include "framework/datasets/signed_distance.hpp"

namespace dtsl::dataset_detail {

namespace {

constexpr double kLength = 2.0;  // the plates' size along x

struct Hole {
  double x, y, radius;
};

/// The plate of `width` x `thickness` (length kLength) with plan corners rounded by `corner`, minus the
/// holes, rims rounded over `rim_blend`; genus = number of holes.
ImplicitSurface plate_with_holes(double width, double thickness, double corner, std::vector<Hole> holes,
                                 double rim_blend, double margin) {
  const double half_t = 0.5 * thickness;
  // The flat region the slab surrounds: the outline inset by the rim radius.
  const double a = 0.5 * kLength - half_t, b = 0.5 * width - half_t, c = std::max(corner - half_t, 0.0);
  ImplicitSurface s;
  s.f = [=](const Vec3& p) {
    const double d = sdf::rounded_rectangle(p.x(), p.y(), a, b, c);
    double v = std::hypot(std::max(d, 0.0), p.z()) - half_t;
    for (const Hole& h : holes) v = sdf::smooth_difference(v, std::hypot(p.x() - h.x, p.y() - h.y) - h.radius, rim_blend);
    return v;
  };
  s.box.extend(Vec3(-0.5 * kLength - margin, -0.5 * width - margin, -half_t - margin));
  s.box.extend(Vec3(0.5 * kLength + margin, 0.5 * width + margin, half_t + margin));
  s.components = 1;
  s.genus = static_cast<int>(holes.size());
  return s;
}

/// Area of the plate's surface (both faces and the rim, holes' walls included), for a vertex estimate.
double plate_area(double width, double thickness, const std::vector<Hole>& holes) {
  double area = 2.0 * kLength * width + M_PI * 0.5 * thickness * 2.0 * (kLength + width);
  for (const Hole& h : holes) area += 2.0 * M_PI * h.radius * thickness - 2.0 * M_PI * h.radius * h.radius;
  return area;
}

void check_edge_length(double edge_length, double thickness, double area) {
  check_positive("edge_length", edge_length);
  require(edge_length <= 0.25 * thickness * (1.0 + 1e-9), "edge_length",
          "must be at most a quarter of the thickness (" + format_number(0.25 * thickness) +
              ") so the rims are resolved, got " + format_number(edge_length));
  const double vertices = 1.2 * area / (edge_length * edge_length);
  require(vertices <= 2e6, "edge_length",
          "too small for this plate: about " + format_number(std::round(vertices)) + " vertices (at most 2000000), got " +
              format_number(edge_length));
}

// ---- plate_holes ------------------------------------------------------------------------------

struct PlateHolesOptions final : Options {
  double width = 1.2;
  double thickness = 0.16;
  double corner_radius = 0.25;
  std::vector<double> hole_diameters{0.2, 0.1, 0.3};
  double rim_blend = 0.03;
  double edge_length = 0.03;

  void visit(FieldVisitor& v) override {
    v.field("width", width, "size along y; the plate is 2 long (x), so lengths are in the [-1,1] frame");
    v.field("thickness", thickness, "size along z; the rim is a half-round of this diameter");
    v.field("corner_radius", corner_radius, "radius of the plate's corners seen from above (>= thickness / 2)");
    v.field("hole_diameters", hole_diameters,
            "1-5 round through-holes along the x axis, each diameter a fraction (0.05-0.4) of the plate's "
            "length 2; the walls between them and to the ends are equal. Genus = number of holes");
    v.field("rim_blend", rim_blend, "width of the fillet rounding each hole's rims (the surface stays smooth: no sharp rim)");
    v.field("edge_length", edge_length, "target edge length of the ground-truth mesh (finer where it curves)");
  }

  /// The holes' centres and radii: in a row on y = 0, walls all equal.
  std::vector<Hole> holes() const {
    const double sum = std::accumulate(hole_diameters.begin(), hole_diameters.end(), 0.0) * kLength;
    const double wall = (kLength - sum) / static_cast<double>(hole_diameters.size() + 1);
    std::vector<Hole> out;
    double x = -0.5 * kLength + wall;
    for (const double d : hole_diameters) {
      out.push_back({x + 0.5 * d * kLength, 0.0, 0.5 * d * kLength});
      x += d * kLength + wall;
    }
    return out;
  }
  /// The narrowest wall the holes leave: between two holes, to the plate's ends or to its sides.
  double min_wall() const {
    const std::vector<Hole> h = holes();
    double wall = (kLength - std::accumulate(hole_diameters.begin(), hole_diameters.end(), 0.0) * kLength) /
                  static_cast<double>(hole_diameters.size() + 1);
    for (const Hole& x : h) wall = std::min(wall, 0.5 * width - x.radius);
    return wall;
  }

  void check() const override {
    check_range("width", width, 0.2, kLength);
    check_positive("thickness", thickness);
    require(thickness <= 0.5 * width, "thickness",
            "must be at most half the width (" + format_number(0.5 * width) + "), got " + format_number(thickness));
    require(corner_radius >= 0.5 * thickness && corner_radius <= 0.5 * width, "corner_radius",
            "must be in [thickness / 2, width / 2] = [" + format_number(0.5 * thickness) + ", " +
                format_number(0.5 * width) + "], got " + format_number(corner_radius));
    require(!hole_diameters.empty() && hole_diameters.size() <= 5, "hole_diameters",
            "must list 1 to 5 diameters, got " + std::to_string(hole_diameters.size()));
    for (const double d : hole_diameters)
      require(d >= 0.05 && d <= 0.4, "hole_diameters",
              "each must be in [0.05, 0.4] (a fraction of the plate's length), got " + format_number(d));
    require(rim_blend > 0.0 && rim_blend <= 0.5 * thickness, "rim_blend",
            "must be in (0, thickness / 2 = " + format_number(0.5 * thickness) + "], got " + format_number(rim_blend));
    // Walls at least a thickness wide and beyond the fillets: a thinner wall is another test (lattice).
    const double need = std::max(thickness, 2.0 * rim_blend);
    require(min_wall() >= need - 1e-9, "hole_diameters",
            "leave a wall of " + format_number(min_wall()) + " (between holes, to the ends or the sides), less than " +
                format_number(need) + " (the thickness); use smaller holes, fewer holes or a wider plate");
    check_edge_length(edge_length, thickness, plate_area(width, thickness, holes()));
  }
};

class PlateHoles final : public ShapeSource {
 public:
  Options& options() override { return o_; }
  ShapeData load() override {
    const double margin = 0.5 * o_.thickness;
    ShapeData d;
    d.mesh = mesh_implicit_surface(
        plate_with_holes(o_.width, o_.thickness, o_.corner_radius, o_.holes(), o_.rim_blend, margin),
        o_.edge_length, "shape 'plate_holes'");
    d.exact = true;
    return d;
  }

 private:
  PlateHolesOptions o_;
};

// ---- high_genus -------------------------------------------------------------------------------

struct HighGenusOptions final : Options {
  int rows = 4;
  int columns = 6;
  double hole_fraction = 0.55;
  double thickness = 0.35;
  double border = 0.6;
  double edge_length = 0.02;

  void visit(FieldVisitor& v) override {
    v.field("rows", rows, "holes along y; genus = rows * columns");
    v.field("columns", columns, "holes along x; the slab is 2 long, so the hole pitch is 2 / (columns + 2 border)");
    v.field("hole_fraction", hole_fraction, "hole diameter as a fraction of the pitch (the rest is wall)");
    v.field("thickness", thickness, "slab thickness as a fraction of the pitch");
    v.field("border", border, "solid border beyond the outer holes' cells, as a fraction of the pitch");
    v.field("edge_length", edge_length, "target edge length of the ground-truth mesh (finer where it curves)");
  }

  double pitch() const { return kLength / (columns + 2.0 * border); }
  double width() const { return pitch() * (rows + 2.0 * border); }
  std::vector<Hole> holes() const {
    std::vector<Hole> out;
    const double p = pitch();
    for (int i = 0; i < rows; ++i)
      for (int j = 0; j < columns; ++j)
        out.push_back({(j - 0.5 * (columns - 1)) * p, (i - 0.5 * (rows - 1)) * p, 0.5 * hole_fraction * p});
    return out;
  }

  void check() const override {
    check_range("rows", rows, 1, 12);
    check_range("columns", columns, 1, 12);
    require(rows <= columns, "rows", "must be at most columns (x is the slab's long side), got rows=" +
                                         std::to_string(rows) + ", columns=" + std::to_string(columns));
    check_range("hole_fraction", hole_fraction, 0.2, 0.8);
    check_range("thickness", thickness, 0.05, 1.0);
    check_range("border", border, 0.3, 2.0);
    check_edge_length(edge_length, thickness * pitch(), plate_area(width(), thickness * pitch(), holes()));
  }
};

class HighGenus final : public ShapeSource {
 public:
  Options& options() override { return o_; }
  ShapeData load() override {
    const double p = o_.pitch(), t = o_.thickness * p;
    // Walls are (1 - hole_fraction) pitch wide; the rim fillets take at most a third of them.
    const double blend = std::min(0.25 * t, (1.0 - o_.hole_fraction) * p / 3.0);
    ShapeData d;
    d.mesh = mesh_implicit_surface(plate_with_holes(o_.width(), t, 0.5 * p, o_.holes(), blend, 0.5 * t),
                                   o_.edge_length, "shape 'high_genus'");
    d.exact = true;
    return d;
  }

 private:
  HighGenusOptions o_;
};

}  // namespace

void register_plate_shapes() {
  shape_sources().add("plate_holes", "rounded plate with 1-5 round through-holes in a row (genus = holes)",
                      [] { return std::make_unique<PlateHoles>(); });
  shape_sources().add("high_genus", "slab with a rows x columns grid of round through-holes (genus rows * columns)",
                      [] { return std::make_unique<HighGenus>(); });
}

}  // namespace dtsl::dataset_detail
