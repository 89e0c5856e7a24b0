// Samplers: requested counts, points on the surface with its normals, and a non-uniform sampler whose
// density really varies by the configured ratio (measured as points per area in two regions).
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <functional>

#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "framework/core/sampling.hpp"
#include "framework/datasets/dataset.hpp"

using namespace dtsl;

namespace {

template <class Plugin>
std::unique_ptr<Plugin> make(Registry<Plugin>& registry, const std::string& type, const std::string& yaml = "{}") {
  register_dataset_plugins();
  auto p = registry.create(type, "test");
  apply_yaml(p->options(), YAML::Load(yaml), "test");
  return p;
}

/// Points per unit area in the part of the surface where `inside` holds (faces by their centroid).
double density(const TriangleMesh& mesh, const PointCloud& cloud, const std::function<bool(const Vec3&)>& inside) {
  double area = 0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& t = mesh.faces[f];
    if (inside((mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0))
      area += face_area(mesh, static_cast<int>(f));
  }
  std::size_t n = 0;
  for (const Vec3& p : cloud.points) n += inside(p) ? 1 : 0;
  return static_cast<double>(n) / area;
}

}  // namespace

TEST_CASE("vertices: the mesh's vertices with its normals", "[datasets][samplers]") {
  ShapeData sphere = make(shape_sources(), "sphere", "{subdivisions: 3}")->load();
  std::mt19937_64 rng(1);
  const PointCloud c = make(samplers(), "vertices")->sample(sphere, rng);
  REQUIRE(c.size() == sphere.mesh->vertices.size());
  REQUIRE(c.has_normals());
  for (std::size_t i = 0; i < c.size(); ++i) {
    CHECK(c.points[i] == sphere.mesh->vertices[i]);
    CHECK(c.normals[i] == sphere.mesh->normals[i]);
  }
}

TEST_CASE("vertices: without mesh normals, area-weighted face normals; stray vertices skipped",
          "[datasets][samplers]") {
  ShapeData d;
  d.mesh = TriangleMesh();
  d.mesh->vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {5, 5, 5}};  // vertex 4 is in no face
  d.mesh->faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};               // outward tetrahedron
  std::mt19937_64 rng(1);
  const PointCloud c = make(samplers(), "vertices")->sample(d, rng);
  REQUIRE(c.size() == 4);
  REQUIRE(c.has_normals());
  // Vertex 0 touches three faces of area 1/2 with normals -x, -y, -z.
  CHECK((c.normals[0] - Vec3(-1, -1, -1).normalized()).norm() < 1e-12);
  // Vertex 3 touches faces -x, -y (area 1/2) and the slanted one (area sqrt(3)/2, normal (1,1,1)/sqrt 3).
  const Vec3 n3 = (Vec3(-0.5, 0, 0) + Vec3(0, -0.5, 0) + 0.5 * Vec3(1, 1, 1)).normalized();
  CHECK((c.normals[3] - n3).norm() < 1e-12);
}

TEST_CASE("area: the requested count, on the surface, with the face's normal", "[datasets][samplers]") {
  ShapeData sphere = make(shape_sources(), "sphere")->load();
  std::mt19937_64 rng(7);
  const PointCloud c = make(samplers(), "area", "{count: 12345}")->sample(sphere, rng);
  REQUIRE(c.size() == 12345);
  REQUIRE(c.has_normals());
  for (std::size_t i = 0; i < c.size(); ++i) {
    REQUIRE(std::abs(c.points[i].norm() - 1.0) < 1e-3);  // inside a chord of the unit sphere
    REQUIRE(std::abs(c.normals[i].norm() - 1.0) < 1e-12);
    REQUIRE(c.normals[i].dot(c.points[i]) > 0.99);  // outward
  }
}

TEST_CASE("area: uniform by default, density_ratio varies density along an axis", "[datasets][samplers]") {
  ShapeData sphere = make(shape_sources(), "sphere")->load();
  const TriangleMesh& m = *sphere.mesh;
  // By Archimedes, a sphere's area is uniform in x, so the slabs at both ends have equal area.
  auto low = [](const Vec3& p) { return p.x() < -0.8; };
  auto high = [](const Vec3& p) { return p.x() > 0.8; };

  std::mt19937_64 rng(11);
  const PointCloud uniform = make(samplers(), "area", "{count: 100000}")->sample(sphere, rng);
  CHECK(density(m, uniform, high) / density(m, uniform, low) == Approx(1.0).epsilon(0.08));

  const PointCloud graded = make(samplers(), "area", "{count: 100000, density_ratio: 8}")->sample(sphere, rng);
  // density = 8^t with t = (x+1)/2: the mean over t in [0.9, 1] over the mean over [0, 0.1] is 8^0.9.
  const double measured = density(m, graded, high) / density(m, graded, low);
  INFO("density ratio high/low slab: " << measured << ", expected " << std::pow(8.0, 0.9));
  CHECK(measured == Approx(std::pow(8.0, 0.9)).epsilon(0.1));

  const PointCloud along_z =
      make(samplers(), "area", "{count: 100000, density_ratio: 8, density_axis: z}")->sample(sphere, rng);
  auto top = [](const Vec3& p) { return p.z() > 0.8; };
  auto bottom = [](const Vec3& p) { return p.z() < -0.8; };
  CHECK(density(m, along_z, top) / density(m, along_z, bottom) == Approx(std::pow(8.0, 0.9)).epsilon(0.1));
  CHECK(density(m, along_z, high) / density(m, along_z, low) == Approx(1.0).epsilon(0.1));
}

TEST_CASE("area: radial density grows away from the centre", "[datasets][samplers]") {
  // A torus (R = 1, r = 0.4) reaches from 0.6 to 1.4 from its centre: density 10^(distance / 1.4).
  ShapeData torus = make(shape_sources(), "torus")->load();
  std::mt19937_64 rng(3);
  const PointCloud c =
      make(samplers(), "area", "{count: 100000, density_ratio: 10, density_axis: radial}")->sample(torus, rng);
  // Regions by the angle around the tube, v = atan2(z, rho - R), cut along grid lines of the mesh
  // (multiples of 2 pi / 64), so each face lies wholly in one region and the areas are exact.
  auto tube_angle = [](const Vec3& p) { return std::atan2(p.z(), std::hypot(p.x(), p.y()) - 1.0); };
  auto inner = [&](const Vec3& p) { return std::abs(tube_angle(p)) > 0.75 * M_PI; };  // facing the hole
  auto outer = [&](const Vec3& p) { return std::abs(tube_angle(p)) < 0.25 * M_PI; };  // facing away
  const double measured = density(*torus.mesh, c, outer) / density(*torus.mesh, c, inner);
  // Expected: the area-weighted mean of 10^(distance / 1.4) over each band, from the mesh's faces.
  auto mean_weight = [&](const std::function<bool(const Vec3&)>& inside) {
    double area = 0, weighted = 0;
    for (std::size_t f = 0; f < torus.mesh->faces.size(); ++f) {
      const Face& t = torus.mesh->faces[f];
      const Vec3 centroid = (torus.mesh->vertices[t[0]] + torus.mesh->vertices[t[1]] + torus.mesh->vertices[t[2]]) / 3.0;
      if (!inside(centroid)) continue;
      const double a = face_area(*torus.mesh, static_cast<int>(f));
      area += a;
      weighted += a * std::pow(10.0, centroid.norm() / 1.4);
    }
    return weighted / area;
  };
  const double expected = mean_weight(outer) / mean_weight(inner);
  INFO("outer/inner density: " << measured << ", expected " << expected);
  CHECK(measured == Approx(expected).epsilon(0.03));
  CHECK(measured > 2.5);
}

TEST_CASE("none: passes the shape's own points on", "[datasets][samplers]") {
  ShapeData d;
  d.points = PointCloud();
  d.points->points = {{0, 0, 0}, {1, 2, 3}};
  std::mt19937_64 rng(1);
  const PointCloud c = make(samplers(), "none")->sample(d, rng);
  CHECK(c.points == d.points->points);
  CHECK_THROWS_AS(make(samplers(), "none")->sample(make(shape_sources(), "sphere")->load(), rng), AlgorithmError);
  CHECK_THROWS_AS(make(samplers(), "vertices")->sample(d, rng), AlgorithmError);
}

TEST_CASE("sampler options are checked, naming the field", "[datasets][samplers][bad]") {
  CHECK_THROWS_WITH(make(samplers(), "area", "{count: 0}"), Catch::StartsWith("test.count: must be in [1, "));
  CHECK_THROWS_WITH(make(samplers(), "area", "{density_ratio: 0.5}"),
                    Catch::StartsWith("test.density_ratio: must be in [1, "));
  CHECK_THROWS_WITH(make(samplers(), "area", "{density_axis: w}"),
                    Catch::StartsWith("test.density_axis: must be one of {x, y, z, radial}, got 'w'"));
  CHECK_THROWS_WITH(make(samplers(), "vertices", "{count: 5}"), Catch::Contains("test.count: unknown key"));
}
