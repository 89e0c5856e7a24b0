// Paper §3.1: foot points, signed displacements and the three closest-triangle cases of Fig. 2.
#include <catch2/catch.hpp>
#include <chrono>
#include <iostream>
#include <random>

#include "algorithms/displacement/projection.hpp"
#include "tests/displacement/implicits.hpp"
#include "tests/displacement/support.hpp"

using namespace dtsl;
using namespace dtsl::test;

namespace {

// Brute-force closest point over all faces.
double brute_distance(const TriangleMesh& m, const Vec3& q) {
  double best = 1e300;
  for (const Face& f : m.faces) {
    Vec3 b;
    best = std::min(best, (closest_point_on_triangle(q, m.vertices[f[0]], m.vertices[f[1]], m.vertices[f[2]], b) - q).norm());
  }
  return best;
}

}  // namespace

TEST_CASE("closest point on a triangle: the three Voronoi cases", "[displacement][projection]") {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  Vec3 w;
  CHECK((closest_point_on_triangle(Vec3(-1, -1, 1), a, b, c, w) - a).norm() == Approx(0).margin(1e-15));
  CHECK(w == Vec3(1, 0, 0));
  CHECK((closest_point_on_triangle(Vec3(0.5, -1, 2), a, b, c, w) - Vec3(0.5, 0, 0)).norm() == Approx(0).margin(1e-15));
  CHECK(w.z() == 0.0);
  CHECK(w.x() == Approx(0.5));
  closest_point_on_triangle(Vec3(0.2, 0.3, -4), a, b, c, w);
  CHECK(w.isApprox(Vec3(0.5, 0.2, 0.3)));
}

TEST_CASE("projection: foot points, d_k and the vertex / edge / face cases on a sphere", "[displacement][projection]") {
  const double r = 0.6;
  const SphereSdf f(r);
  const TriangleMesh mesh = base_mesh(f, Vec3(r, 0, 0), 0.05);
  const MeshLocator locator(mesh);

  // Points right above a vertex, an edge midpoint and a face centroid, 0.1 outside / 0.05 inside.
  const Face& face = mesh.faces[17];
  const Vec3 v = mesh.vertices[face[0]];
  const Vec3 mid = 0.5 * (mesh.vertices[face[0]] + mesh.vertices[face[1]]);
  const Vec3 cen = (mesh.vertices[face[0]] + mesh.vertices[face[1]] + mesh.vertices[face[2]]) / 3.0;
  const std::vector<Vec3> points = {v.normalized() * (r + 0.1), mid.normalized() * (r + 0.1),
                                    cen.normalized() * (r - 0.05)};
  const ProjectionResult pr = project_data(f, locator, points);
  REQUIRE(pr.newton_failures == 0);
  CHECK(pr.displacements[0] == Approx(0.1).margin(1e-9));
  CHECK(pr.displacements[1] == Approx(0.1).margin(1e-9));
  CHECK(pr.displacements[2] == Approx(-0.05).margin(1e-9));

  // Vertex case: the vertex itself, associated with its whole fan.
  const MeshLocation& lv = pr.locations[0];
  CHECK(lv.kind == ProjectionCase::vertex);
  CHECK(lv.element[0] == face[0]);
  CHECK(locator.closest_faces(lv).size() == locator.vertex_faces(face[0]).size());
  // Edge case: both triangles of the edge, the midpoint at barycentric 1/2 (|a| = |b| on the sphere).
  const MeshLocation& le = pr.locations[1];
  CHECK(le.kind == ProjectionCase::edge);
  CHECK(le.element[0] == std::min(face[0], face[1]));
  CHECK(le.element[1] == std::max(face[0], face[1]));
  CHECK((le.point - mid).norm() < 1e-6);
  const std::vector<int> ef = locator.closest_faces(le);
  REQUIRE(ef.size() == 2);
  CHECK((ef[0] == 17 || ef[1] == 17));
  // Face case: that face, all barycentrics well inside.
  const MeshLocation& lf = pr.locations[2];
  CHECK(lf.kind == ProjectionCase::face);
  CHECK(lf.face == 17);
  CHECK(lf.barycentric.minCoeff() > 0.2);
  // I_i: the vertex point is on every triangle of the fan, the edge point on both triangles of the edge.
  for (int fi : locator.vertex_faces(face[0])) CHECK(std::count(pr.triangle_points[fi].begin(), pr.triangle_points[fi].end(), 0) == 1);
  CHECK(pr.triangle_points[17].size() == 3);  // all three points touch face 17
  CHECK(pr.cases[static_cast<int>(ProjectionCase::vertex)] == 1);
  CHECK(pr.cases[static_cast<int>(ProjectionCase::edge)] == 1);
  CHECK(pr.cases[static_cast<int>(ProjectionCase::face)] == 1);
}

TEST_CASE("projection: d_k is the analytic distance; the one-ring finds the true closest triangle",
          "[displacement][projection]") {
  const double r = 0.6;
  const SphereSdf f(r);
  const TriangleMesh mesh = base_mesh(f, Vec3(r, 0, 0), 0.04);
  const MeshLocator locator(mesh);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> radius(0.4, 0.8);
  std::vector<Vec3> points;
  for (const Vec3& d : fibonacci_directions(3000)) points.push_back(radius(rng) * d);
  const ProjectionResult pr = project_data(f, locator, points);
  REQUIRE(pr.newton_failures == 0);
  double worst_d = 0, worst_onering = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    worst_d = std::max(worst_d, std::abs(pr.displacements[k] - (points[k].norm() - r)));
    worst_onering = std::max(worst_onering, pr.locations[k].distance - brute_distance(mesh, pr.foot_points[k]));
    // locate_from a neighbour of the answer's vertex walks to the same place.
    const int guess = locator.vertex_neighbours(pr.locations[k].closest_vertex).front();
    CHECK(locator.locate_from(pr.foot_points[k], guess).distance == Approx(pr.locations[k].distance).margin(1e-12));
  }
  CHECK(worst_d < 1e-9);
  CHECK(worst_onering < 1e-12);  // the one-ring search is exact for foot points on this mesh
  INFO(pr.summary().dump());
  CHECK(pr.cases[static_cast<int>(ProjectionCase::face)] > 2000);
}

TEST_CASE("vertex grid: nearest agrees with brute force; timing", "[displacement][projection][grid]") {
  const SphereSdf f(0.6);
  const TriangleMesh mesh = base_mesh(f, Vec3(0.6, 0, 0), 0.02);
  const MeshLocator locator(mesh);
  const PointGrid grid(mesh.vertices, locator.mean_edge_length());
  std::mt19937_64 rng(3);
  // Queries where Phase 2 makes them: near the surface (data and foot points).
  std::uniform_real_distribution<double> u(0.5, 0.7);
  std::vector<Vec3> queries;
  for (const Vec3& d : fibonacci_directions(2000)) queries.push_back(u(rng) * d);
  auto t0 = std::chrono::steady_clock::now();
  std::vector<double> dg(queries.size());
  for (std::size_t i = 0; i < queries.size(); ++i) grid.nearest(queries[i], &dg[i]);
  auto t1 = std::chrono::steady_clock::now();
  std::vector<double> db(queries.size(), 1e300);
  for (std::size_t i = 0; i < queries.size(); ++i)
    for (const Vec3& v : mesh.vertices) db[i] = std::min(db[i], (v - queries[i]).norm());
  auto t2 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < queries.size(); ++i) CHECK(dg[i] == Approx(db[i]).margin(1e-15));
  const double tg = std::chrono::duration<double>(t1 - t0).count(), tb = std::chrono::duration<double>(t2 - t1).count();
  std::cout << "[vertex grid] " << mesh.vertices.size() << " vertices, " << queries.size()
            << " queries within 0.1 of the surface: grid " << tg * 1e6 / queries.size() << " us/query, brute force "
            << tb * 1e6 / queries.size() << " us/query\n";
  CHECK(tg < tb);
}

TEST_CASE("locator on a general mesh (Phase 3 use): one-ring vs exact distances of the data",
          "[displacement][projection]") {
  // The locator without f: data points (not foot points) against a mesh off f = 0. Measures how often
  // the closest vertex's one-ring misses the exact closest triangle (the documented limit).
  const SphereSdf f(0.6);
  TriangleMesh mesh = base_mesh(f, Vec3(0.6, 0, 0), 0.04);
  for (Vec3& v : mesh.vertices) v *= 1.0 + 0.05 * std::sin(5 * v.x()) * std::cos(4 * v.z());
  const MeshLocator locator(mesh);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> N(0.0, 0.01);
  std::vector<Vec3> points;
  for (const Vec3& d : fibonacci_directions(3000)) points.push_back((0.6 + N(rng)) * d);
  std::size_t exact = 0;
  double worst = 0.0, sum_excess = 0.0;
  int previous = -1;
  for (const Vec3& p : points) {
    const double truth = brute_distance(mesh, p);
    const MeshLocation a = locator.locate(p);
    const MeshLocation b = locator.locate_from(p, previous);  // walk from the previous point's vertex
    previous = a.closest_vertex;
    CHECK(a.distance >= truth - 1e-12);
    CHECK(b.distance >= truth - 1e-12);
    if (a.distance - truth < 1e-12) ++exact;
    worst = std::max(worst, a.distance - truth);
    sum_excess += a.distance - truth;
  }
  std::cout << "[locator, data off the mesh] exact for " << exact << " / " << points.size()
            << " points; worst excess " << worst << ", mean excess " << sum_excess / points.size() << "\n";
  CHECK(exact > 0.95 * points.size());
  CHECK(worst < 0.1 * locator.mean_edge_length());
}
