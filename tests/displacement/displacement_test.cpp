// Paper §3.2: the displaced mesh lowers the error; holes are filled without a crease; flips are found.
#include <catch2/catch.hpp>
#include <iostream>
#include <random>

#include "algorithms/displacement/curvature.hpp"
#include "algorithms/displacement/displacement.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/displacement/implicits.hpp"
#include "tests/displacement/support.hpp"

using namespace dtsl;
using namespace dtsl::test;

namespace {

// The bumpy sphere's radius along the unit direction d: R + a sin(3 theta) cos(2 phi).
double bumpy_radius(const Vec3& d, double R, double a) {
  const double theta = std::acos(d.z()), phi = std::atan2(d.y(), d.x());
  return R + a * std::sin(3 * theta) * std::cos(2 * phi);
}

// n points of the bumpy sphere, each moved along its direction by Gaussian noise (none at 0).
std::vector<Vec3> bumpy_sphere(int n, double R, double a, double noise, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> N(0.0, noise > 0 ? noise : 1.0);
  std::vector<Vec3> out;
  for (const Vec3& d : fibonacci_directions(n)) out.push_back((bumpy_radius(d, R, a) + (noise > 0 ? N(rng) : 0.0)) * d);
  return out;
}

// The capped ball: a ball of radius 0.62 cut flat at x = 0.45 (a circular crease of 90 - 43 degrees),
// 6000 points of it, with its distance to a point and a point's distance to the crease circle.
struct CappedBall {
  double R = 0.62, cut = 0.45;
  std::vector<Vec3> points;
  CappedBall() {
    for (const Vec3& d : fibonacci_directions(6000)) {
      Vec3 p = R * d;
      if (p.x() > cut) p.x() = cut;
      points.push_back(p);
    }
  }
  double to_truth(const Vec3& v) const { return std::abs(std::max(v.norm() - R, v.x() - cut)); }
  double from_crease(const Vec3& v) const {
    return std::hypot(v.x() - cut, std::hypot(v.y(), v.z()) - std::sqrt(R * R - cut * cut));
  }
};

}  // namespace

TEST_CASE("displacement lowers e_avr on a bumpy, noisy sphere", "[displacement]") {
  const SphereSdf f(0.6);
  const TriangleMesh base = base_mesh(f, Vec3(0.6, 0, 0), 0.03);
  const std::vector<Vec3> points = bumpy_sphere(40000, 0.63, 0.02, 0.002, 1);
  // The paper's fixed filter (the noise-adaptive one has its own test below, on fewer points: its wide
  // windows over 40k points are slow under the sanitizers).
  DisplacementOptions paper;
  paper.filter = "gaussian";
  const DisplacementResult r = displace_mesh(f, base, points, paper);
  const PointErrors before = point_errors(points, base), after = point_errors(points, r.mesh);
  std::cout << "[bumpy sphere] e_avr " << before.e_avr * 1e3 << "e-3 -> " << after.e_avr * 1e3 << "e-3, e_max "
            << before.e_max * 1e3 << "e-3 -> " << after.e_max * 1e3 << "e-3; summary " << r.summary.dump() << "\n";
  CHECK(after.e_avr < 0.15 * before.e_avr);
  CHECK(after.e_max < before.e_max);
  CHECK(r.flipped_faces.empty());
  CHECK(r.hole_vertices.empty());
  CHECK_FALSE(r.needs_refinement);
  CHECK(mesh_stats(r.mesh).watertight);
  // The summary's one-ring errors agree with the exact ones.
  CHECK(r.summary["errors_after"]["e_avr"].get<double>() == Approx(after.e_avr).epsilon(0.02));
  CHECK(r.summary["errors_before"]["e_avr"].get<double>() == Approx(before.e_avr).epsilon(0.02));
}

TEST_CASE("displacement on an ellipsoid and a rounded box: lower error, no flips", "[displacement]") {
  const Ellipsoid ell(Vec3(0.7, 0.5, 0.4));
  const RoundedBox box(Vec3(0.6, 0.5, 0.4), 0.15);
  const ImplicitFunction* shapes[] = {&ell, &box};
  const Vec3 seeds[] = {Vec3(0.7, 0, 0), Vec3(0.6, 0, 0)};
  for (int s = 0; s < 2; ++s) {
    const ImplicitFunction& f = *shapes[s];
    const TriangleMesh base = base_mesh(f, seeds[s], 0.03);
    // Data: the base vertices pushed along the normal by a smooth field of +-0.02 with noise.
    std::mt19937_64 rng(5);
    std::normal_distribution<double> N(0.0, 0.001);
    std::vector<Vec3> points;
    for (const Vec3& v : base.vertices) {
      const Vec3 n = f.gradient(v).normalized();
      points.push_back(v + (0.02 * std::sin(4 * v.x()) * std::cos(3 * v.y()) + 0.01 + N(rng)) * n);
    }
    DisplacementOptions o;
    o.filter = "gaussian";  // the paper's filter (the noise-adaptive one is tested on the noisy sphere below)
    const DisplacementResult r = displace_mesh(f, base, points, o);
    const PointErrors before = point_errors(points, base), after = point_errors(points, r.mesh);
    std::cout << "[" << (s ? "rounded box" : "ellipsoid") << "] e_avr " << before.e_avr * 1e3 << "e-3 -> "
              << after.e_avr * 1e3 << "e-3; flips " << r.flipped_faces.size() << "\n";
    CHECK(after.e_avr < 0.25 * before.e_avr);
    CHECK(flipped_faces(base, r.mesh.vertices).empty());  // every face, not only those the check tests
    CHECK(mesh_stats(r.mesh).watertight);
  }
}

TEST_CASE("holes: the harmonic fill and the fairings span a removed ball without a crease", "[displacement][holes]") {
  const SphereSdf f(0.6);
  const TriangleMesh base = base_mesh(f, Vec3(0.6, 0, 0), 0.03);
  const Vec3 centre = Vec3(0.2, 0.3, 0.5).normalized() * 0.63;
  std::vector<Vec3> points;
  for (const Vec3& d : fibonacci_directions(30000)) {
    const Vec3 p = (0.63 + 0.01 * d.x() * d.y()) * d;  // a smooth, varying offset
    if ((p - centre).norm() > 0.25) points.push_back(p);
  }
  DisplacementOptions harmonic_only;
  harmonic_only.hole_fill = "harmonic";
  const DisplacementResult h = displace_mesh(f, base, points, harmonic_only);
  REQUIRE(h.hole_vertices.size() > 50);
  CHECK(h.summary["hole_vertices_filled"].get<std::size_t>() == h.hole_vertices.size());
  CHECK(h.summary["hole_vertices_faired"].get<std::size_t>() == 0);
  std::vector<char> hole(base.vertices.size(), 0);
  for (int v : h.hole_vertices) hole[v] = 1;
  // Unfilled (d = 0 at the hole vertices, the base surface's place): the step the fill avoids.
  TriangleMesh unfilled = h.mesh;
  for (int v : h.hole_vertices) unfilled.vertices[v] = base.vertices[v];
  const auto before = dihedral_angles(base), unfilled_after = dihedral_angles(unfilled);
  // The largest change of a dihedral angle near the hole (within 0.4 of its centre: the rim and inside).
  const auto worst_change = [&](const TriangleMesh& m) {
    const auto after = dihedral_angles(m);
    double worst = 0;
    for (const auto& e : before) {
      const Vec3 mid = 0.5 * (base.vertices[e.first.first] + base.vertices[e.first.second]);
      if ((mid - centre).norm() <= 0.4) worst = std::max(worst, std::abs(after.at(e.first) - e.second));
    }
    return worst;
  };
  const double deg = 180.0 / M_PI, worst_unfilled = worst_change(unfilled);
  for (const char* fill : {"harmonic", "membrane", "thin_plate"}) {
    DisplacementOptions o;
    o.hole_fill = fill;
    const DisplacementResult a = displace_mesh(f, base, points, o);
    CHECK(a.hole_vertices == h.hole_vertices);
    CHECK(a.summary["hole_fairing_failures"].get<std::size_t>() == 0);
    const bool faired = std::string(fill) != "harmonic";
    CHECK(a.summary["hole_vertices_faired"].get<std::size_t>() == (faired ? a.hole_vertices.size() : 0));
    // d is the normal part of every move; without fairing the move is exactly d n (Eq. 2), faired hole
    // vertices also slide, and nothing else changes between the treatments.
    double slide = 0.0;
    for (std::size_t v = 0; v < base.vertices.size(); ++v) {
      const Vec3 move = a.mesh.vertices[v] - base.vertices[v];
      CHECK(move.dot(a.mesh.normals[v]) == Approx(a.vertex_displacement[v]).margin(1e-12));
      if (!hole[v]) CHECK(a.mesh.vertices[v] == h.mesh.vertices[v]);
      else slide = std::max(slide, (move - a.vertex_displacement[v] * a.mesh.normals[v]).norm());
    }
    CHECK((faired ? slide > 0.0 : slide < 1e-12));
    CHECK(mesh_stats(a.mesh).watertight);
    CHECK(a.flipped_faces.empty());
    const double worst = worst_change(a.mesh);
    std::cout << "[hole] " << fill << ": " << a.hole_vertices.size() << " hole vertices; max dihedral change near "
              << "the hole " << worst * deg << " deg, unfilled (d = 0) " << worst_unfilled * deg << " deg\n";
    if (std::string(fill) == "membrane") {
      // The membrane spans the hole by a near-minimal surface: a flat cap (the sphere's sagitta over a
      // hole of radius 0.25 is 0.05), kinked at the rim but far less than the unfilled step.
      CHECK(worst_unfilled > 1.5 * worst);
      for (int v : a.hole_vertices) CHECK(a.mesh.vertices[v].norm() == Approx(0.605).margin(0.037));
      continue;
    }
    CHECK(worst * deg < 2.0);
    CHECK(worst_unfilled > 5 * worst);
    // The filled surface over the hole sits near the data's radius, not back on the base sphere.
    for (int v : a.hole_vertices) CHECK(a.mesh.vertices[v].norm() == Approx(0.63).margin(0.012));
  }
}

TEST_CASE("holes: a base mesh the fairing cannot take keeps the harmonic fill and says why", "[displacement][holes]") {
  const SphereSdf f(0.6);
  TriangleMesh base = base_mesh(f, Vec3(0.6, 0, 0), 0.05);
  base.faces.push_back(base.faces.front());  // a repeated face: two faces too many on its edges
  const Vec3 centre = Vec3(0.2, 0.3, 0.5).normalized() * 0.63;
  std::vector<Vec3> points;
  for (const Vec3& d : fibonacci_directions(8000))
    if ((0.63 * d - centre).norm() > 0.25) points.push_back(0.63 * d);
  const DisplacementResult r = displace_mesh(f, base, points, DisplacementOptions{});
  REQUIRE(r.hole_vertices.size() > 10);
  CHECK(r.summary["hole_vertices_faired"].get<std::size_t>() == 0);
  CHECK(r.summary["hole_fairing_skipped"].get<std::string>().find("non-manifold") != std::string::npos);
  CHECK(r.summary["hole_vertices_filled"].get<std::size_t>() == r.hole_vertices.size());
  for (int v : r.hole_vertices) CHECK(r.mesh.vertices[v].norm() == Approx(0.63).margin(0.012));
}

TEST_CASE("curvature check: a large displacement at a thin concave neck is flagged", "[displacement][curvature]") {
  // Neck radius 0.08, concave along the axis with radius ~ 0.08 / 1.5 ~ 0.05 (R'' ~ 18.7 at x = 0).
  const Dumbbell f(0.08, 1.5);
  const TriangleMesh base = base_mesh(f, Vec3(0.5, std::sqrt(0.75 * (0.0064 + 0.375)), 0), 0.015);
  REQUIRE(mesh_stats(base).watertight);
  // Data: a cylinder of radius 0.3 around the neck (the truth has no neck): displacements up to ~ +0.22,
  // far beyond the neck's concave radius, so the normals cross and triangles flip.
  std::vector<Vec3> points;
  for (int i = 0; i < 60; ++i)
    for (int j = 0; j < 120; ++j) {
      const double x = -0.2 + 0.4 * i / 59.0, a = 2 * M_PI * j / 120.0;
      points.emplace_back(x, 0.3 * std::cos(a), 0.3 * std::sin(a));
    }
  DisplacementOptions o;
  // The bulbs have no data: two 20k-vertex holes, whose fairing (3 s each) is not what this tests.
  o.hole_fill = "harmonic";
  const DisplacementResult r = displace_mesh(f, base, points, o);
  std::cout << "[neck] " << r.summary.dump() << "\n";
  CHECK(r.at_risk_vertices.size() > 0);
  CHECK(r.flipped_faces.size() > 0);
  CHECK(r.needs_refinement);
  CHECK(r.summary["flipped_faces"].get<std::size_t>() == r.flipped_faces.size());
  // Every flipped face is around a vertex at risk (that is where the check looks).
  CHECK(flipped_faces(base, r.mesh.vertices).size() == r.flipped_faces.size());
}

namespace {

// Mean radial distance of the vertices from the noise-free bumpy sphere bumpy_sphere samples.
double mean_distance_to_bumpy_sphere(const TriangleMesh& m, double R, double a) {
  double sum = 0.0;
  for (const Vec3& v : m.vertices) sum += std::abs(v.norm() - bumpy_radius(v.normalized(), R, a));
  return sum / static_cast<double>(m.vertices.size());
}

}  // namespace

TEST_CASE("on noisy data the filter widens where the shape allows: closer to the true surface", "[displacement][noise]") {
  const SphereSdf f(0.6);
  const TriangleMesh base = base_mesh(f, Vec3(0.6, 0, 0), 0.03);
  const std::vector<Vec3> points = bumpy_sphere(8000, 0.63, 0.02, 0.004, 2);
  DisplacementOptions paper;
  paper.filter = "gaussian";  // the fixed filter: noise-free data assumed
  DisplacementOptions adaptive;  // the defaults: noise estimated from the data
  const DisplacementResult fixed = displace_mesh(f, base, points, paper);
  const DisplacementResult widened = displace_mesh(f, base, points, adaptive);
  const double e_fixed = mean_distance_to_bumpy_sphere(fixed.mesh, 0.63, 0.02);
  const double e_widened = mean_distance_to_bumpy_sphere(widened.mesh, 0.63, 0.02);
  std::cout << "[noise] bumpy sphere, noise 0.004: distance to the truth " << e_fixed << " (fixed filter) -> "
            << e_widened << " (ICI widths); summary " << widened.summary.dump() << "\n";
  CHECK(widened.summary["noise_sigma"].get<double>() == Approx(0.004).epsilon(0.2));
  CHECK(widened.summary["filter_widened"].get<bool>());
  CHECK(widened.summary["vertex_sigma_mean"].get<double>() > 1.5 * widened.summary["sigma"].get<double>());
  CHECK(e_widened < 0.6 * e_fixed);
  // The final mesh's RMS offset is about the true noise (0.004 along the normal), not below it.
  CHECK(widened.summary["residual_rms"].get<double>() > 0.85 * 0.004);
  CHECK(widened.flipped_faces.empty());
  CHECK(mesh_stats(widened.mesh).watertight);
  // The noise measured once serves the refine-on-flip rounds: given back, the same mesh, no estimate.
  const DisplacementResult again = displace_mesh(f, base, points, adaptive, &widened.scale);
  CHECK(again.mesh.vertices == widened.mesh.vertices);
  CHECK_FALSE(again.summary["noise_estimated"].get<bool>());
}

TEST_CASE("data read as noise-free take the noise-free filter", "[displacement][noise]") {
  const SphereSdf f(0.6);
  const TriangleMesh base = base_mesh(f, Vec3(0.6, 0, 0), 0.03);
  const std::vector<Vec3> points = bumpy_sphere(15000, 0.63, 0.02, 0.0, 3);
  DisplacementOptions estimated;
  const DisplacementResult b = displace_mesh(f, base, points, estimated);
  DataScale noise_free;  // the noise-free filter at the measured spacing
  noise_free.spacing = b.scale.spacing;
  const DisplacementResult a = displace_mesh(f, base, points, estimated, &noise_free);
  std::cout << "[noise] clean bumpy sphere: estimated noise " << b.summary["noise_sigma"] << ", widths "
            << b.summary["filter_widths"] << ", mean width " << b.summary["vertex_sigma_mean"] << "\n";
  // Read as (next to) nothing, below the floor: the noise-free filter (no ICI widths), to the last bit.
  CHECK(b.summary["noise_estimate"]["sigma"].get<double>() < 1e-4);
  CHECK(b.summary["noise_sigma"].get<double>() == 0.0);
  CHECK_FALSE(b.summary["filter_widened"].get<bool>());
  CHECK(a.mesh.vertices == b.mesh.vertices);
}

TEST_CASE("data sparser than the mesh: a filter as wide as the spacing that fits a plane leaves no ripple",
          "[displacement][sparse]") {
  const SphereSdf f(0.6);
  const TriangleMesh base = base_mesh(f, Vec3(0.6, 0, 0), 0.03);
  // ~1200 points on a bumpy sphere: spacing ~0.065, about two of the base mesh's edges.
  const std::vector<Vec3> points = bumpy_sphere(1200, 0.63, 0.02, 0.0, 4);
  const auto rms_to_truth = [](const TriangleMesh& m) {
    double sum2 = 0.0;
    for (const Vec3& v : m.vertices) sum2 += std::pow(v.norm() - bumpy_radius(v.normalized(), 0.63, 0.02), 2);
    return std::sqrt(sum2 / static_cast<double>(m.vertices.size()));
  };
  DisplacementOptions paper;
  paper.filter = "gaussian";   // the paper's filter
  DisplacementOptions sparse;  // the default, on data read as noise-free
  const DisplacementResult a = displace_mesh(f, base, points, paper), b = displace_mesh(f, base, points, sparse);
  const double e_paper = rms_to_truth(a.mesh), e_sparse = rms_to_truth(b.mesh);
  std::cout << "[sparse] bumpy sphere, 1200 points: RMS distance to the truth " << e_paper * 1e3 << "e-3 (paper's width "
            << a.summary["sigma"] << ") -> " << e_sparse * 1e3 << "e-3 (width " << b.summary["sigma"] << ", spacing "
            << b.summary["data_spacing"] << ")\n";
  // The measured spacing sets the width, and the wider filter fits a plane at (nearly) every vertex.
  const double spacing = b.summary["data_spacing"].get<double>();
  CHECK(spacing == Approx(0.065).epsilon(0.25));
  CHECK(b.summary["sigma"].get<double>() == Approx(spacing));
  CHECK(b.summary["base_filter_fits"].get<bool>());
  CHECK(b.summary["regression_degree_vertices"][1].get<std::size_t>() > 0.9 * base.vertices.size());
  CHECK_FALSE(a.summary["base_filter_fits"].get<bool>());
  CHECK(e_sparse < 0.6 * e_paper);
  CHECK(b.summary["noise_sigma"].get<double>() == 0.0);
  CHECK(b.flipped_faces.empty());
  CHECK(mesh_stats(b.mesh).watertight);
  // A spacing given is used as it is.
  DataScale given;
  given.spacing = 0.05;
  CHECK(displace_mesh(f, base, points, sparse, &given).summary["sigma"].get<double>() == Approx(0.05));
}

TEST_CASE("data sparser than the mesh: vertices with no data within the paper's support are faired, a hole's margin "
          "as the gaps option says",
          "[displacement][sparse][holes]") {
  const SphereSdf f(0.6);
  const TriangleMesh base = base_mesh(f, Vec3(0.6, 0, 0), 0.03);
  // ~500 points (spacing ~0.1, three of the base mesh's edges) with a cap removed around +z.
  const double cap = 0.45;
  std::vector<Vec3> points;
  for (const Vec3& p : bumpy_sphere(500, 0.63, 0.02, 0.0, 4))
    if ((p - Vec3(0, 0, 0.63)).norm() > cap) points.push_back(p);
  const double paper = DisplacementOptions().sigma_factor * MeshLocator(base).mean_edge_length();
  // The distance from x to the nearest datum's foot on the base (the radial projection onto the sphere).
  const auto nearest = [&](const Vec3& x) {
    double best = 1e9;
    for (const Vec3& p : points) best = std::min(best, (p.normalized() * 0.6 - x).norm());
    return best;
  };
  const auto from_cap = [&](const Vec3& x) { return (x.normalized() * 0.63 - Vec3(0, 0, 0.63)).norm() - cap; };
  for (const std::string gaps : {"fit", "margin"}) {
    DYNAMIC_SECTION("gaps: " << gaps) {
      DisplacementOptions o;  // the default filter, on data read as noise-free
      o.gaps = gaps;
      o.rim_offset = 0;  // the rim test grows holes by its own rule (hole_rim.hpp): off, the filter's alone
      const DisplacementResult r = displace_mesh(f, base, points, o);
      REQUIRE(r.summary["base_filter_fits"].get<bool>());
      const double wide = r.summary["sigma"].get<double>();
      REQUIRE(wide > 2 * paper);
      std::vector<char> hole(base.vertices.size(), 0);
      for (int v : r.hole_vertices) hole[v] = 1;
      std::size_t gap = 0, gap_holes = 0, margin = 0, margin_holes = 0;
      for (std::size_t v = 0; v < base.vertices.size(); ++v) {
        const Vec3& x = base.vertices[v];
        const double near = nearest(x);
        // Data within the paper's support (a foot within 2 widths weighs enough): never a hole.
        if (near < 2 * paper) CHECK_FALSE(hole[v]);
        if (near <= 3.5 * paper) continue;  // out of every foot's reach at the paper's width below
        if (from_cap(x) > 3 * wide) ++gap, gap_holes += hole[v];              // between the data
        if (from_cap(x) < 0 && near < 1.5 * wide) ++margin, margin_holes += hole[v];  // just inside the cap
      }
      std::cout << "[sparse gaps] gaps " << gaps << ": " << r.hole_vertices.size() << " hole vertices of "
                << base.vertices.size() << "; between the data " << gap_holes << " of " << gap
                << ", inside the cap's edge " << margin_holes << " of " << margin << "\n";
      REQUIRE(gap > 100);
      REQUIRE(margin > 10);
      // fit: the wide fit reaches every vertex between the data. margin: none of them keeps it.
      CHECK(gap_holes == (gaps == "fit" ? 0 : gap));
      // Both: the fit carries the data's surface across the cap's edge.
      CHECK(margin_holes == 0);
      CHECK(mesh_stats(r.mesh).watertight);
      CHECK(r.flipped_faces.empty());
    }
  }
  DisplacementOptions bad;
  bad.gaps = "holes";
  CHECK_THROWS_WITH(bad.check(), Catch::Contains("gaps") && Catch::Contains("holes"));
}

// Where the data are sparse throughout, a vertex farther than the reach (in the median spacing) from the
// data is a gap between them, not a hole's edge: the margin is measured in the local spacing there.
TEST_CASE("sparse half of a sphere: no hole margin where the gaps are a local spacing wide",
          "[displacement][sparse][holes]") {
  const SphereSdf f(0.6);
  const TriangleMesh base = base_mesh(f, Vec3(0.6, 0, 0), 0.03);
  // The upper half densely sampled (it sets the median spacing), the lower half 25x more sparsely.
  std::vector<Vec3> points;
  for (const Vec3& p : bumpy_sphere(3000, 0.63, 0.02, 0.0, 5))
    if (p.z() > 0) points.push_back(p);
  for (const Vec3& p : bumpy_sphere(120, 0.63, 0.02, 0.0, 6))
    if (p.z() < 0) points.push_back(p);
  const double paper = DisplacementOptions().sigma_factor * MeshLocator(base).mean_edge_length();
  const auto nearest = [&](const Vec3& x) {
    double best = 1e9;
    for (const Vec3& p : points) best = std::min(best, (p.normalized() * 0.6 - x).norm());
    return best;
  };
  DisplacementOptions o;
  o.rim_offset = 0;
  const DisplacementResult r = displace_mesh(f, base, points, o);
  REQUIRE(r.summary["base_filter_fits"].get<bool>());
  const double wide = r.summary["sigma"].get<double>();
  std::vector<char> hole(base.vertices.size(), 0);
  for (int v : r.hole_vertices) hole[v] = 1;
  std::size_t beyond_reach = 0, gap = 0, gap_holes = 0;
  for (std::size_t v = 0; v < base.vertices.size(); ++v) {
    const Vec3& x = base.vertices[v];
    // The sparse half beyond the density step at z = 0: its dense side is a hole's edge, whose margins
    // reach a filter's reach from seeds up to about that far below it.
    if (x.z() > -6 * wide) continue;
    const double near = nearest(x);
    if (near > 3 * wide) ++beyond_reach;  // a hole's edge by the median spacing
    if (near > 3.5 * paper) ++gap, gap_holes += hole[v];
  }
  std::cout << "[sparse half] beyond the median reach " << beyond_reach << ", between the data " << gap_holes
            << " of " << gap << " faired\n";
  REQUIRE(beyond_reach > 0);
  REQUIRE(gap > 100);
  CHECK(gap_holes == gap);  // a margin counted in the median spacing keeps the fit on most of them
  CHECK(mesh_stats(r.mesh).watertight);
}

TEST_CASE("fine residual passes: the paper's narrow mean of what the wide fit left brings the mesh to the data",
          "[displacement][sparse][fine]") {
  // The capped ball of the test above: the wide fit rounds the crease; its residuals there are what the
  // narrow passes take up. Far from the crease the wide fit leaves little, so little changes.
  // The base a little inside the data (|d| ~ 5e-3 on the sphere part, well below fine_max_offset x the
  // filter's width): Phase 1 ends near the data.
  const SphereSdf f(0.615);
  const TriangleMesh base = base_mesh(f, Vec3(0.615, 0, 0), 0.03);
  const CappedBall ball;
  const std::vector<Vec3>& points = ball.points;
  const auto to_truth = [&](const Vec3& v) { return ball.to_truth(v); };
  const auto from_crease = [&](const Vec3& v) { return ball.from_crease(v); };
  DisplacementOptions wide;
  wide.fine_residual_passes = 0;
  DisplacementOptions fine = wide;
  fine.fine_residual_passes = DisplacementOptions().fine_residual_passes;
  REQUIRE(fine.fine_residual_passes > 0);  // on by default
  const DisplacementResult a = displace_mesh(f, base, points, wide), b = displace_mesh(f, base, points, fine);
  CHECK(a.summary["fine_residual_passes"].get<int>() == 0);
  CHECK(b.summary["fine_residual_passes"].get<int>() == fine.fine_residual_passes);
  REQUIRE(b.summary["base_filter_fits"].get<bool>());
  const double sigma = b.summary["sigma"].get<double>();
  double near_a = 0.0, near_b = 0.0, far_a = 0.0, far_b = 0.0;
  int near = 0, far = 0;
  for (std::size_t v = 0; v < base.vertices.size(); ++v) {
    const double c = from_crease(base.vertices[v]);
    const double ea = std::pow(to_truth(a.mesh.vertices[v]), 2), eb = std::pow(to_truth(b.mesh.vertices[v]), 2);
    if (c < 1.5 * sigma) ++near, near_a += ea, near_b += eb;
    else if (c > 4 * sigma) ++far, far_a += ea, far_b += eb;
  }
  REQUIRE(near > 0);
  REQUIRE(far > 0);
  std::cout << "[fine] capped sphere: " << b.summary["fine_residual_vertices"].get<int>() << " of " << base.vertices.size()
            << " vertices take the narrow passes; RMS to the truth near the crease " << std::sqrt(near_a / near) * 1e3
            << "e-3 -> " << std::sqrt(near_b / near) * 1e3 << "e-3, far " << std::sqrt(far_a / far) * 1e3 << "e-3 -> "
            << std::sqrt(far_b / far) * 1e3 << "e-3; data e_avr " << a.summary["errors_after"]["e_avr"].get<double>() * 1e3
            << "e-3 -> " << b.summary["errors_after"]["e_avr"].get<double>() * 1e3 << "e-3\n";
  // The data fit closer (e_avr of the data to the mesh), and the vertices are no farther from the truth:
  // at the crease a vertex cannot lie on the sharp edge, so its distance falls little (1.28 -> 1.24e-3
  // here); what the passes add is where the data are.
  CHECK(b.summary["errors_after"]["e_avr"].get<double>() < 0.7 * a.summary["errors_after"]["e_avr"].get<double>());
  CHECK(near_b < near_a);
  CHECK(far_b < 1.1 * far_a + 1e-12);
  CHECK(b.flipped_faces.empty());
  CHECK(mesh_stats(b.mesh).watertight);
  // Noisy data keep their widened fits and passes: the fine passes do not apply.
  DataScale noisy;
  noisy.noise_sigma = 0.002;
  CHECK(displace_mesh(f, base, points, fine, &noisy).summary["fine_residual_passes"].get<int>() == 0);
}

TEST_CASE("holes: rim vertices whose feet lie to one side join the hole, and the fill starts where the data do",
          "[displacement][holes]") {
  const SphereSdf f(0.6);
  const TriangleMesh base = base_mesh(f, Vec3(0.6, 0, 0), 0.03);
  // Data off the base by an offset that bends (so a one-sided linear fit at the rim extrapolates it
  // wrongly), with a ball removed where it bends most.
  const auto radius = [](const Vec3& d) { return 0.62 + 0.06 * d.x() * d.x(); };
  const Vec3 centre = Vec3(1.0, 0.6, 0.3).normalized() * 0.65;
  const double hole = 0.25;
  std::vector<Vec3> points;
  for (const Vec3& d : fibonacci_directions(12000)) {
    const Vec3 p = radius(d) * d;
    if ((p - centre).norm() > hole) points.push_back(p);
  }
  DisplacementOptions plain;
  plain.rim_offset = 0.0;  // the weight test's holes alone
  const DisplacementResult a = displace_mesh(f, base, points, plain);
  REQUIRE(a.hole_vertices.size() > 30);
  // Graph distance (edges) of every vertex from the weight test's holes.
  const MeshLocator locator(base);
  const std::vector<std::vector<int>>& neighbours = locator.vertex_neighbours();
  std::vector<int> steps(base.vertices.size(), -1), queue(a.hole_vertices.begin(), a.hole_vertices.end());
  for (int v : queue) steps[v] = 0;
  for (std::size_t q = 0; q < queue.size(); ++q)
    for (int u : neighbours[queue[q]])
      if (steps[u] < 0) steps[u] = steps[queue[q]] + 1, queue.push_back(u);
  {
    const int rings = 1;
    DisplacementOptions rim;
    REQUIRE(rim.rim_offset > 0);  // on by default
    const DisplacementResult b = displace_mesh(f, base, points, rim);
    // The weight test's holes stay holes; the rim adds vertices beside them, and only there.
    std::vector<char> in_a(base.vertices.size(), 0), in_b(base.vertices.size(), 0);
    for (int v : a.hole_vertices) in_a[v] = 1;
    for (int v : b.hole_vertices) in_b[v] = 1;
    std::size_t added = 0;
    double farthest = 0.0;
    for (std::size_t v = 0; v < base.vertices.size(); ++v) {
      if (in_a[v]) CHECK(in_b[v]);
      if (in_b[v] && !in_a[v]) ++added, farthest = std::max(farthest, (base.vertices[v] - centre).norm());
    }
    CHECK(added > 0);
    CHECK(b.summary["hole_rim_vertices"].get<std::size_t>() == added);
    CHECK(a.summary["hole_rim_vertices"].get<std::size_t>() == 0);
    CHECK(farthest < hole + (rings + 1) * 0.03);  // one ring of ~0.03 edges around the hole
    for (std::size_t v = 0; v < base.vertices.size(); ++v)
      if (in_b[v] && !in_a[v]) CHECK((steps[v] >= 1 && steps[v] <= rings));
    // Over the union of both hole regions, the filled surface is nearer the data's surface with the rim.
    double worst_a = 0.0, worst_b = 0.0, sum_a = 0.0, sum_b = 0.0;
    for (int v : b.hole_vertices) {
      const auto off = [&](const Vec3& x) { return std::abs(x.norm() - radius(x.normalized())); };
      worst_a = std::max(worst_a, off(a.mesh.vertices[v])), sum_a += off(a.mesh.vertices[v]);
      worst_b = std::max(worst_b, off(b.mesh.vertices[v])), sum_b += off(b.mesh.vertices[v]);
    }
    const double n = static_cast<double>(b.hole_vertices.size());
    std::cout << "[hole rim] " << a.hole_vertices.size() << " hole vertices, " << added
              << " rim vertices added; distance to the data's surface over the hole: mean " << sum_a / n * 1e3
              << "e-3 -> " << sum_b / n * 1e3 << "e-3, max " << worst_a * 1e3 << "e-3 -> " << worst_b * 1e3 << "e-3\n";
    CHECK(sum_b < 0.5 * sum_a);
    CHECK(worst_b < 0.5 * worst_a);
    CHECK(mesh_stats(b.mesh).watertight);
    CHECK(b.flipped_faces.empty());
  }
}
