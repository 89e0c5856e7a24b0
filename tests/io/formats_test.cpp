// Every supported variant of every format, from small hand-written files (tests/data/io/) and
// generated binary PLYs covering each scalar type, both byte orders and both spellings of type names.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "framework/io/io.hpp"
#include "io_test_support.hpp"

using dtsl::Face;
using dtsl::PointCloud;
using dtsl::TriangleMesh;
using dtsl::Vec3;
using dtsl::test::Bytes;
using dtsl::test::data_path;

TEST_CASE("file_extension is the lower-cased suffix of the file name", "[io]") {
  REQUIRE(dtsl::file_extension("a/b/model.PLY") == "ply");
  REQUIRE(dtsl::file_extension("x.tar.gz") == "gz");
  REQUIRE(dtsl::file_extension("dir.d/noext") == "");
  REQUIRE(dtsl::file_extension("/tmp/.hidden") == "");
  REQUIRE(dtsl::file_extension("") == "");
}

TEST_CASE("ascii PLY with extra properties, list properties and extra elements", "[io][ply]") {
  const TriangleMesh m = dtsl::read_mesh(data_path("extra_props.ply"));
  REQUIRE(m.vertices == std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)});
  REQUIRE(m.faces == std::vector<Face>{{0, 1, 2}, {0, 2, 3}});  // the quad, fan-triangulated
  REQUIRE(m.has_normals());
  for (const Vec3& n : m.normals) REQUIRE(n == Vec3(0, 0, 1));
}

namespace {

struct TypeCase {
  const char* name;       // as written in the header
  const char* alias;      // the other spelling
  int bytes;
  bool is_signed, is_float;
};
const TypeCase kTypes[] = {{"char", "int8", 1, true, false},       {"uchar", "uint8", 1, false, false},
                           {"short", "int16", 2, true, false},     {"ushort", "uint16", 2, false, false},
                           {"int", "int32", 4, true, false},       {"uint", "uint32", 4, false, false},
                           {"float", "float32", 4, true, true},    {"double", "float64", 8, true, true}};

// Appends `v` encoded as type `t`.
void put(Bytes& b, const TypeCase& t, double v) {
  if (t.is_float) {
    if (t.bytes == 4) b.put(static_cast<float>(v));
    else b.put(v);
    return;
  }
  switch (t.bytes) {
    case 1: t.is_signed ? (void)b.put(static_cast<std::int8_t>(v)) : (void)b.put(static_cast<std::uint8_t>(v)); break;
    case 2: t.is_signed ? (void)b.put(static_cast<std::int16_t>(v)) : (void)b.put(static_cast<std::uint16_t>(v)); break;
    default: t.is_signed ? (void)b.put(static_cast<std::int32_t>(v)) : (void)b.put(static_cast<std::uint32_t>(v)); break;
  }
}

std::string format_line(int encoding) {
  static const char* names[] = {"ascii", "binary_little_endian", "binary_big_endian"};
  return std::string("format ") + names[encoding] + " 1.0\n";
}

}  // namespace

TEST_CASE("PLY: coordinates of every scalar type, in every encoding and spelling", "[io][ply]") {
  dtsl::test::TempDir tmp;
  for (const TypeCase& t : kTypes)
    for (int encoding = 0; encoding < 3; ++encoding)
      for (bool alias : {false, true}) {
        const char* type = alias ? t.alias : t.name;
        INFO(type << " " << format_line(encoding));
        std::string file = "ply\n" + format_line(encoding) + "element vertex 2\n";
        for (const char* axis : {"x", "y", "z"}) file += std::string("property ") + type + " " + axis + "\n";
        file += "end_header\n";
        const double values[2][3] = {{1, 2, 3}, {t.is_signed ? -4.0 : 4.0, 127, 0}};
        if (encoding == 0) {
          file += "1 2 3\n" + std::to_string(static_cast<int>(values[1][0])) + " 127 0\n";
        } else {
          Bytes b(encoding == 2);
          for (const auto& p : values)
            for (double v : p) put(b, t, v);
          file += b.str();
        }
        const PointCloud c = dtsl::read_points(tmp.write("t.ply", file));
        REQUIRE(c.points == std::vector<Vec3>{Vec3(1, 2, 3), Vec3(values[1][0], 127, 0)});
        REQUIRE_FALSE(c.has_normals());
      }
}

TEST_CASE("PLY: face lists of every integer count and index type", "[io][ply]") {
  dtsl::test::TempDir tmp;
  for (const TypeCase& count : kTypes)
    for (const TypeCase& index : kTypes) {
      if (count.is_float || index.is_float) continue;
      for (int encoding = 1; encoding < 3; ++encoding) {
        INFO("list " << count.name << " " << index.alias << " " << format_line(encoding));
        std::string file = "ply\n" + format_line(encoding) +
                           "element vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
                           "element face 2\nproperty list " + count.name + " " + index.alias + " vertex_indices\n"
                           "end_header\n";
        Bytes b(encoding == 2);
        for (int v = 0; v < 4; ++v) b.put(double(v & 1)).put(double(v >> 1)).put(0.0);
        put(b, count, 3);
        for (int i : {0, 1, 3}) put(b, index, i);
        put(b, count, 4);
        for (int i : {0, 3, 2, 1}) put(b, index, i);
        const TriangleMesh m = dtsl::read_mesh(tmp.write("f.ply", file + b.str()));
        REQUIRE(m.faces == std::vector<Face>{{0, 1, 3}, {0, 3, 2}, {0, 2, 1}});
      }
    }
}

TEST_CASE("PLY: big- and little-endian files with skipped scalar and list properties and elements", "[io][ply]") {
  dtsl::test::TempDir tmp;
  for (bool big : {false, true}) {
    INFO((big ? "big" : "little") << " endian");
    std::string header = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                         " 1.0\n"
                         "comment everything but x y z nx ny nz and vertex_indices must be skipped\n"
                         "element camera 1\nproperty double fov\nproperty list uchar float params\n"
                         "element vertex 3\n"
                         "property uchar red\nproperty float x\nproperty list ushort int16 tags\n"
                         "property double y\nproperty int16 z\nproperty int8 nx\nproperty uint8 ny\n"
                         "property float64 nz\nproperty uint32 id\n"
                         "element face 1\nproperty int32 flags\nproperty list uint8 uint16 vertex_index\n"
                         "property list int8 float32 texcoord\n"
                         "element empty 1000000000000\n"  // no properties: occupies no bytes
                         "end_header\n";
    Bytes b(big);
    b.put(0.75).put(std::uint8_t{2}).put(1.0f).put(2.0f);  // camera
    const double xyz[3][3] = {{0.5, -1.25, 7}, {2, 3, -4}, {-8, 0.125, 100}};
    for (int v = 0; v < 3; ++v) {
      b.put(std::uint8_t{200}).put(static_cast<float>(xyz[v][0]));
      b.put(std::uint16_t(v)); // list of v tags
      for (int k = 0; k < v; ++k) b.put(std::int16_t(-k));
      b.put(xyz[v][1]).put(static_cast<std::int16_t>(xyz[v][2]));
      b.put(std::int8_t{-1}).put(std::uint8_t{0}).put(0.0).put(std::uint32_t{123456});
    }
    b.put(std::int32_t{-7}).put(std::uint8_t{3}).put(std::uint16_t{2}).put(std::uint16_t{1}).put(std::uint16_t{0});
    b.put(std::int8_t{2}).put(0.5f).put(0.25f);
    const TriangleMesh m = dtsl::read_mesh(tmp.write("e.ply", header + b.str()));
    REQUIRE(m.vertices == std::vector<Vec3>{Vec3(0.5, -1.25, 7), Vec3(2, 3, -4), Vec3(-8, 0.125, 100)});
    REQUIRE(m.faces == std::vector<Face>{{2, 1, 0}});
    REQUIRE(m.normals == std::vector<Vec3>(3, Vec3(-1, 0, 0)));
  }
}

TEST_CASE("OBJ with every face-corner form, negative indices, polygons and comments", "[io][obj]") {
  const TriangleMesh m = dtsl::read_mesh(data_path("slashes.obj"));
  REQUIRE(m.vertices.size() == 6);
  REQUIRE(m.vertices[5] == Vec3(2, 1, 0));
  // f -4/-3/-1 -2 -1 -3//-1 after 6 vertices is the quad 2 4 5 3.
  REQUIRE(m.faces == std::vector<Face>{{0, 1, 2}, {0, 2, 3}, {0, 1, 2}, {0, 2, 3}, {2, 4, 5}, {2, 5, 3}});
  REQUIRE_FALSE(m.has_normals());  // vertices 4 and 5 have no normal in any face
}

TEST_CASE("OBJ: per-vertex normals from face corners", "[io][obj]") {
  dtsl::test::TempDir tmp;
  const std::string path = tmp.write("n.obj",
                                     "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 -1\nvn 0 0 1\n"
                                     "f 1//2 2//2 3//2\n");
  const TriangleMesh m = dtsl::read_mesh(path);
  REQUIRE(m.normals == std::vector<Vec3>(3, Vec3(0, 0, 1)));
}

TEST_CASE("OFF with counts on the OFF line, comments, blank lines and quads", "[io][off]") {
  const TriangleMesh m = dtsl::read_mesh(data_path("cube_quads.off"));
  REQUIRE(m.vertices.size() == 8);
  REQUIRE(m.vertices[7] == Vec3(0, 1, 1));
  REQUIRE(m.faces.size() == 12);
  REQUIRE(m.faces[0] == Face{0, 3, 2});
  REQUIRE(m.faces[1] == Face{0, 2, 1});
  REQUIRE(m.faces[7] == Face{2, 7, 6});  // the quad with a colour after its indices
  REQUIRE_FALSE(m.has_normals());
}

TEST_CASE("NOFF with counts on their own line, CRLF line ends and a pentagon", "[io][off]") {
  const TriangleMesh m = dtsl::read_mesh(data_path("pentagon_noff.off"));
  REQUIRE(m.vertices.size() == 5);
  REQUIRE(m.vertices[4] == Vec3(-0.5, 1, 0));
  REQUIRE(m.faces == std::vector<Face>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}});
  REQUIRE(m.normals == std::vector<Vec3>(5, Vec3(0, 0, 1)));
}

TEST_CASE("XYZ with normals, comments, blank lines and signed exponents", "[io][xyz]") {
  const PointCloud c = dtsl::read_points(data_path("points_normals.xyz"));
  REQUIRE(c.points == std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1.5, -2, 3), Vec3(-1e-3, 200, 0.25)});
  REQUIRE(c.normals == std::vector<Vec3>{Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, 1, 0)});
}

TEST_CASE("XYZ without normals", "[io][xyz]") {
  dtsl::test::TempDir tmp;
  const PointCloud c = dtsl::read_points(tmp.write("p.xyz", "1 2 3\n4 5 6"));  // no final newline
  REQUIRE(c.points == std::vector<Vec3>{Vec3(1, 2, 3), Vec3(4, 5, 6)});
  REQUIRE_FALSE(c.has_normals());
}

TEST_CASE("PCD (ascii, through PCL) with extra fields and normals", "[io][pcd]") {
  const PointCloud c = dtsl::read_points(data_path("points_rgb.pcd"));
  REQUIRE(c.points == std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 2, 3), Vec3(-1.5, 0.25, 8)});
  REQUIRE(c.normals == std::vector<Vec3>{Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, 1, 0)});
}

// A manual check, not a test: `test_io "[.perf]"`.
TEST_CASE("a 1M-point binary PLY loads quickly", "[.perf]") {
  dtsl::test::TempDir tmp;
  PointCloud c;
  for (int i = 0; i < 1000000; ++i) {
    c.points.emplace_back(i * 1e-6, -i * 2e-6, 0.5);
    c.normals.emplace_back(0, 0, 1);
  }
  const std::string path = tmp.path("big.ply");
  dtsl::write_points(path, c);
  const auto start = std::chrono::steady_clock::now();
  const PointCloud back = dtsl::read_points(path);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  WARN("read 1M points with normals in " << seconds << " s");
  REQUIRE(back.size() == c.size());
}
