// Write then read back, for every format and encoding: points with and without normals, and meshes.
// Text and PLY writers are exact (shortest round-trip decimal, or binary doubles); PCD stores float32.
#include <catch2/catch.hpp>
#include <random>

#include "framework/io/io.hpp"
#include "io_test_support.hpp"

using dtsl::PointCloud;
using dtsl::TriangleMesh;
using dtsl::Vec3;
using dtsl::WriteOptions;

namespace {

// Coordinates that a lossy printer would change: thirds, tiny and large magnitudes, negative zero.
PointCloud sample_cloud(bool normals) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  PointCloud c;
  c.points = {Vec3(1.0 / 3.0, -2.0 / 7.0, 1e-300), Vec3(12345.678901234, -0.0, 5e-8)};
  for (int i = 0; i < 200; ++i) c.points.emplace_back(u(rng), u(rng) * 1e3, u(rng) * 1e-3);
  if (normals)
    for (std::size_t i = 0; i < c.points.size(); ++i) c.normals.push_back(Vec3(u(rng), u(rng), u(rng)).normalized());
  return c;
}

TriangleMesh octahedron(bool normals) {
  TriangleMesh m;
  m.vertices = {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1.0 / 3.0, 0), Vec3(0, -1, 0), Vec3(0, 0, 0.1), Vec3(0, 0, -1)};
  m.faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  if (normals)
    for (const Vec3& v : m.vertices) m.normals.push_back(v.normalized());
  return m;
}

void require_same(const std::vector<Vec3>& a, const std::vector<Vec3>& b, double tolerance) {
  REQUIRE(a.size() == b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    INFO("index " << i << ": " << a[i].transpose() << " vs " << b[i].transpose());
    if (tolerance == 0.0) REQUIRE(a[i] == b[i]);
    else REQUIRE((a[i] - b[i]).norm() <= tolerance * (1.0 + a[i].norm()));
  }
}

}  // namespace

TEST_CASE("points round trip through every format", "[io][roundtrip]") {
  dtsl::test::TempDir tmp;
  struct Case {
    const char* name;
    bool binary;
    double tolerance;
  };
  const Case cases[] = {{"p.ply", true, 0.0}, {"p.ply", false, 0.0}, {"p.obj", false, 0.0}, {"p.off", false, 0.0},
                        {"p.xyz", false, 0.0}, {"p.pcd", true, 1e-6}, {"p.pcd", false, 1e-6}, {"P.PLY", true, 0.0}};
  for (const Case& k : cases)
    for (bool normals : {false, true}) {
      INFO(k.name << (k.binary ? " binary" : " ascii") << (normals ? " with normals" : " without normals"));
      const PointCloud in = sample_cloud(normals);
      const std::string path = tmp.path(k.name);
      WriteOptions options;
      options.binary = k.binary;
      dtsl::write_points(path, in, options);
      const PointCloud out = dtsl::read_points(path);
      require_same(in.points, out.points, k.tolerance);
      REQUIRE(out.has_normals() == normals);
      if (normals) require_same(in.normals, out.normals, k.tolerance);
    }
}

TEST_CASE("meshes round trip through PLY (both encodings), OBJ and OFF", "[io][roundtrip]") {
  dtsl::test::TempDir tmp;
  for (const char* name : {"m.ply", "m.obj", "m.off"})
    for (bool binary : {true, false})
      for (bool normals : {false, true}) {
        INFO(name << (binary ? " binary" : " ascii") << (normals ? " with normals" : ""));
        const TriangleMesh in = octahedron(normals);
        const std::string path = tmp.path(name);
        WriteOptions options;
        options.binary = binary;
        dtsl::write_mesh(path, in, options);
        const TriangleMesh out = dtsl::read_mesh(path);
        require_same(in.vertices, out.vertices, 0.0);
        REQUIRE(out.faces == in.faces);
        REQUIRE(out.has_normals() == normals);
        if (normals) require_same(in.normals, out.normals, 0.0);
        // read_points of a mesh file gives its vertices (and normals).
        const PointCloud pts = dtsl::read_points(path);
        require_same(in.vertices, pts.points, 0.0);
        REQUIRE(pts.has_normals() == normals);
      }
}

TEST_CASE("PLY writer: binary little-endian by default, ascii on request", "[io][roundtrip]") {
  dtsl::test::TempDir tmp;
  const std::string path = tmp.path("m.ply");
  dtsl::write_mesh(path, octahedron(false));
  std::ifstream in(path, std::ios::binary);
  std::string first, second;
  std::getline(in, first);
  std::getline(in, second);
  REQUIRE(first == "ply");
  REQUIRE(second == "format binary_little_endian 1.0");
  WriteOptions ascii;
  ascii.binary = false;
  dtsl::write_mesh(path, octahedron(false), ascii);
  std::ifstream again(path, std::ios::binary);
  std::getline(again, first);
  std::getline(again, second);
  REQUIRE(second == "format ascii 1.0");
}

TEST_CASE("writes replace the target atomically and leave no temporary behind", "[io][roundtrip]") {
  dtsl::test::TempDir tmp;
  const std::string path = tmp.path("m.off");
  dtsl::write_mesh(path, octahedron(false));
  dtsl::write_mesh(path, octahedron(true));
  REQUIRE(dtsl::read_mesh(path).has_normals());
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(tmp.dir())) {
    (void)e;
    ++files;
  }
  REQUIRE(files == 1);
}
