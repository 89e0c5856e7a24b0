// Fairing of hole vertices (hole_fairing.hpp): what each order reproduces, and what it refuses.
#include <catch2/catch.hpp>

#include <cmath>
#include <iostream>

#include "algorithms/displacement/hole_fairing.hpp"
#include "framework/core/error.hpp"
#include "framework/core/mesh_adjacency.hpp"
#include "implicits.hpp"
#include "support.hpp"

using namespace dtsl;
using namespace dtsl::test;

namespace {

std::vector<std::vector<int>> vertex_neighbours(const TriangleMesh& m) { return mesh_adjacency(m).vertex_neighbours; }

// Largest | |v| - r | over the flagged vertices.
double sphere_deviation(const TriangleMesh& m, const std::vector<char>& flag, double r) {
  double worst = 0.0;
  for (std::size_t v = 0; v < m.vertices.size(); ++v)
    if (flag[v]) worst = std::max(worst, std::abs(m.vertices[v].norm() - r));
  return worst;
}

}  // namespace

TEST_CASE("hole fairing: a flattened cap of a sphere bulges back, thin plate nearer than membrane", "[displacement][holes]") {
  // Phase 1 spans a hole with a near-minimal surface; the cap cut flat here stands for it.
  const double r = 0.6;
  const SphereSdf f(r);
  const TriangleMesh sphere = base_mesh(f, Vec3(r, 0, 0), 0.045);
  const Vec3 axis = Vec3(0.3, -0.2, 0.9).normalized();
  const double plane = r * std::cos(0.5);  // cap of half-angle 0.5 rad (~ 0.29 wide)
  TriangleMesh flat = sphere;
  std::vector<char> free(sphere.vertices.size(), 0);
  for (std::size_t v = 0; v < sphere.vertices.size(); ++v) {
    const double h = sphere.vertices[v].dot(axis);
    if (h <= plane) continue;
    free[v] = 1;
    flat.vertices[v] -= (h - plane) * axis;
  }
  const auto nb = vertex_neighbours(sphere);
  const double flattened = sphere_deviation(flat, free, r);
  REQUIRE(flattened > 0.05);

  TriangleMesh membrane = flat, thin_plate = flat, third = flat;
  const HoleFairingReport a = fair_holes(membrane, free, nb, 0);
  const HoleFairingReport b = fair_holes(thin_plate, free, nb, 1);
  fair_holes(third, free, nb, 2);
  const double dev_membrane = sphere_deviation(membrane, free, r), dev_thin = sphere_deviation(thin_plate, free, r),
               dev_third = sphere_deviation(third, free, r);
  std::cout << "[fairing] cap deviation from the sphere: flattened " << flattened << ", membrane " << dev_membrane
            << ", thin plate " << dev_thin << ", third order " << dev_third << "\n";
  CHECK(b.regions == 1);
  CHECK(b.vertices == static_cast<std::size_t>(std::count(free.begin(), free.end(), 1)));
  CHECK(b.unanchored == 0);
  CHECK(b.failed_regions == 0);
  CHECK(a.regions == 1);
  // The membrane is a minimal surface over the rim: it stays nearly flat. The thin plate continues the
  // sphere's slope across the rim: much nearer the sphere.
  CHECK(dev_membrane > 0.5 * flattened);
  CHECK(dev_thin < 0.2 * flattened);
  CHECK(dev_third < 0.2 * flattened);
  // Vertices off the cap do not move.
  for (std::size_t v = 0; v < flat.vertices.size(); ++v)
    if (!free[v]) CHECK(thin_plate.vertices[v] == flat.vertices[v]);
}

TEST_CASE("hole fairing: a plane stays a plane", "[displacement][holes]") {
  // Constants are in the kernel of every order: vertices pushed off a flat part come back onto it.
  const double r = 0.6;
  const SphereSdf f(r);
  TriangleMesh m = base_mesh(f, Vec3(r, 0, 0), 0.045);
  // Flatten a cap onto z = plane, then lift its inner part: fairing (with the flat ring fixed) must
  // bring the lifted vertices back to z = plane.
  const double plane = r * std::cos(0.6), inner = r * std::cos(0.35);
  std::vector<char> free(m.vertices.size(), 0);
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    const double z = m.vertices[v].z();
    if (z <= plane) continue;
    m.vertices[v].z() = plane;
    if (z > inner) free[v] = 1, m.vertices[v].z() += 0.05 * std::sin(40.0 * m.vertices[v].x());
  }
  const auto nb = vertex_neighbours(m);
  for (int order = 0; order <= 2; ++order) {
    TriangleMesh faired = m;
    fair_holes(faired, free, nb, order);
    for (std::size_t v = 0; v < m.vertices.size(); ++v)
      if (free[v]) CHECK(faired.vertices[v].z() == Approx(plane).margin(1e-7));
  }
}

TEST_CASE("hole fairing: a region above the size limit keeps its positions, a smaller one is faired",
          "[displacement][holes]") {
  const double r = 0.6;
  const SphereSdf f(r);
  const TriangleMesh sphere = base_mesh(f, Vec3(r, 0, 0), 0.05);
  // Two flattened caps on opposite sides, the second about four times the first's area.
  TriangleMesh flat = sphere;
  std::vector<char> free(sphere.vertices.size(), 0), small(sphere.vertices.size(), 0);
  std::size_t small_count = 0, large_count = 0;
  for (std::size_t v = 0; v < sphere.vertices.size(); ++v) {
    const double z = sphere.vertices[v].z(), plane = z > 0 ? r * std::cos(0.35) : -r * std::cos(0.7);
    if (z > 0 ? z <= plane : z >= plane) continue;
    free[v] = 1;
    flat.vertices[v].z() = plane;
    if (z > 0) small[v] = 1, ++small_count;
    else ++large_count;
  }
  REQUIRE(large_count > 2 * small_count);
  const auto nb = vertex_neighbours(sphere);
  TriangleMesh faired = flat;
  const HoleFairingReport rep = fair_holes(faired, free, nb, 1, (small_count + large_count) / 2);
  CHECK(rep.regions == 1);
  CHECK(rep.vertices == small_count);
  CHECK(rep.oversized_regions == 1);
  CHECK(rep.oversized_vertices == large_count);
  CHECK(rep.largest_region == large_count);
  for (std::size_t v = 0; v < sphere.vertices.size(); ++v)
    if (free[v] && !small[v]) CHECK(faired.vertices[v] == flat.vertices[v]);
  CHECK(sphere_deviation(faired, small, r) < 0.5 * sphere_deviation(flat, small, r));
  // Without a limit both are faired.
  TriangleMesh both = flat;
  const HoleFairingReport all = fair_holes(both, free, nb, 1, 0);
  CHECK(all.regions == 2);
  CHECK(all.oversized_regions == 0);
}

TEST_CASE("hole fairing: a region held by a few fixed vertices only is not a hole and keeps its positions",
          "[displacement][holes]") {
  const SphereSdf f(0.6);
  const TriangleMesh m = base_mesh(f, Vec3(0.6, 0, 0), 0.05);
  const auto nb = vertex_neighbours(m);
  // Every vertex free but a handful: one region, far fewer fixed neighbours than sqrt(its size).
  std::vector<char> free(m.vertices.size(), 1);
  for (std::size_t v = 0; v < m.vertices.size(); v += m.vertices.size() / 4) free[v] = 0;
  const std::size_t n = static_cast<std::size_t>(std::count(free.begin(), free.end(), 1));
  TriangleMesh few = m;
  for (Vec3& p : few.vertices) p *= 1.1;  // positions fairing would move
  const TriangleMesh before = few;
  const HoleFairingReport r = fair_holes(few, free, nb, 1);
  CHECK(r.regions == 0);
  CHECK(r.weakly_anchored_regions == 1);
  CHECK(r.weakly_anchored_vertices == n);
  CHECK(r.largest_region == n);
  for (std::size_t v = 0; v < m.vertices.size(); ++v) CHECK(few.vertices[v] == before.vertices[v]);
  // A band of fixed vertices around the equator holds each half by its whole rim: both are faired.
  std::vector<char> halves(m.vertices.size(), 0);
  for (std::size_t v = 0; v < m.vertices.size(); ++v) halves[v] = std::abs(m.vertices[v].z()) > 0.05;
  TriangleMesh held = m;
  const HoleFairingReport h = fair_holes(held, halves, nb, 1);
  CHECK(h.regions == 2);
  CHECK(h.weakly_anchored_regions == 0);
}

TEST_CASE("hole fairing: nothing to continue from, and bad input", "[displacement][holes][errors]") {
  const SphereSdf f(0.6);
  const TriangleMesh m = base_mesh(f, Vec3(0.6, 0, 0), 0.05);
  const auto nb = vertex_neighbours(m);
  // Every vertex free: no fixed rim, the mesh is left as it is.
  TriangleMesh all = m;
  const HoleFairingReport r = fair_holes(all, std::vector<char>(m.vertices.size(), 1), nb, 1);
  CHECK(r.regions == 0);
  CHECK(r.unanchored == m.vertices.size());
  for (std::size_t v = 0; v < m.vertices.size(); ++v) CHECK(all.vertices[v] == m.vertices[v]);
  // No free vertex: nothing happens.
  TriangleMesh none = m;
  CHECK(fair_holes(none, std::vector<char>(m.vertices.size(), 0), nb, 1).regions == 0);

  TriangleMesh copy = m;
  CHECK_THROWS_WITH(fair_holes(copy, std::vector<char>(3, 1), nb, 1), Catch::Contains("free flags"));
  CHECK_THROWS_WITH(fair_holes(copy, std::vector<char>(m.vertices.size(), 1), nb, 4),
                    Catch::Contains("continuity must be 0, 1 or 2, got 4"));
  // A face repeated: the mesh is not edge-manifold.
  TriangleMesh broken = m;
  broken.faces.push_back(broken.faces.front());
  std::vector<char> some(m.vertices.size(), 0);
  some[broken.faces.front()[0]] = 1;
  CHECK_THROWS_WITH(fair_holes(broken, some, nb, 1), Catch::Contains("non-manifold"));
}
