// Every bad input is a FileError whose message names the file, the line (text formats) or the element
// (binary), and what is wrong; nothing crashes, hangs or allocates from an untrusted count.
#include <catch2/catch.hpp>
#include <filesystem>
#include <limits>
#include <string>

#include "framework/io/io.hpp"
#include "io_test_support.hpp"

using Catch::Matchers::Contains;
using dtsl::PointCloud;
using dtsl::TriangleMesh;
using dtsl::Vec3;
using dtsl::test::Bytes;
using dtsl::test::file_error;

namespace {

std::string read_points_error(const std::string& path) {
  return file_error([&] { dtsl::read_points(path); });
}
std::string read_mesh_error(const std::string& path) {
  return file_error([&] { dtsl::read_mesh(path); });
}
// "path:line:" is how FileError names a line.
std::string at_line(const std::string& path, int line) { return path + ":" + std::to_string(line) + ":"; }

const char* const kPlyXyzHeader =
    "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\n";

}  // namespace

TEST_CASE("bad input: a missing file", "[io][bad]") {
  dtsl::test::TempDir tmp;
  for (const char* name : {"none.ply", "none.obj", "none.off", "none.xyz", "none.pcd"}) {
    const std::string path = tmp.path(name);
    const std::string msg = read_points_error(path);
    CHECK_THAT(msg, Contains(path) && Contains("No such file"));
  }
  const std::string path = tmp.path("none.off");
  CHECK_THAT(read_mesh_error(path), Contains(path) && Contains("No such file"));
}

TEST_CASE("bad input: a directory instead of a file", "[io][bad]") {
  dtsl::test::TempDir tmp;
  const std::string path = tmp.path("folder.ply");
  std::filesystem::create_directory(path);
  CHECK_THAT(read_points_error(path), Contains(path) && Contains("not a regular file"));
}

TEST_CASE("bad input: an empty file", "[io][bad]") {
  dtsl::test::TempDir tmp;
  for (const char* name : {"e.ply", "e.obj", "e.off", "e.xyz", "e.pcd"}) {
    const std::string path = tmp.write(name, "");
    CHECK_THAT(read_points_error(path), Contains(path) && Contains("empty"));
  }
}

TEST_CASE("bad input: an unknown or missing extension", "[io][bad]") {
  dtsl::test::TempDir tmp;
  const std::string stl = tmp.write("model.stl", "solid x\n");
  CHECK_THAT(read_points_error(stl), Contains(stl) && Contains("'.stl'") && Contains(".ply"));
  CHECK_THAT(read_mesh_error(stl), Contains(stl) && Contains("'.stl'"));
  const std::string none = tmp.write("model", "1 2 3\n");
  CHECK_THAT(read_points_error(none), Contains(none) && Contains("no file extension"));
  PointCloud c;
  c.points = {Vec3(0, 0, 0)};
  const std::string out = tmp.path("out.vtk");
  CHECK_THAT(file_error([&] { dtsl::write_points(out, c); }), Contains(out) && Contains("'.vtk'"));
  REQUIRE_FALSE(std::filesystem::exists(out));
}

TEST_CASE("bad input: truncated binary PLY data names the element", "[io][bad]") {
  dtsl::test::TempDir tmp;
  // Fixed-size vertices: the header's promise does not fit the bytes that follow.
  Bytes b(false);
  for (int k = 0; k < 7; ++k) b.put(1.0f);  // 2 and a third vertices
  const std::string short_vertices = tmp.write("v.ply", std::string(kPlyXyzHeader) + "end_header\n" + b.str());
  CHECK_THAT(read_points_error(short_vertices),
             Contains(at_line(short_vertices, 3)) && Contains("3 'vertex' elements") && Contains("truncated"));
  // Variable-size faces: the list of face 1 runs past the end of the file.
  Bytes f(false);
  for (int k = 0; k < 9; ++k) f.put(float(k));
  f.put(std::uint8_t{3}).put(0).put(1).put(2);
  f.put(std::uint8_t{3}).put(0).put(1);
  const std::string short_faces =
      tmp.write("f.ply", std::string(kPlyXyzHeader) + "element face 2\nproperty list uchar int vertex_indices\n"
                                                      "end_header\n" + f.str());
  CHECK_THAT(read_mesh_error(short_faces), Contains(short_faces) && Contains("face 1 (of 2)") && Contains("truncated"));
  // A list whose length alone would exceed the file.
  Bytes g(false);
  for (int k = 0; k < 9; ++k) g.put(float(k));
  g.put(std::uint32_t{4000000000u}).put(0).put(1).put(2);
  const std::string huge_list =
      tmp.write("g.ply", std::string(kPlyXyzHeader) + "element face 1\nproperty list uint int vertex_indices\n"
                                                      "end_header\n" + g.str());
  CHECK_THAT(read_mesh_error(huge_list), Contains(huge_list) && Contains("face 0 (of 1)") && Contains("truncated"));
}

TEST_CASE("bad input: a header that promises 10M vertices for a file that holds 3", "[io][bad]") {
  dtsl::test::TempDir tmp;
  Bytes b(false);
  for (int k = 0; k < 9; ++k) b.put(float(k));
  std::string header = kPlyXyzHeader;
  header.replace(header.find("vertex 3"), 8, "vertex 10000000");
  const std::string ply = tmp.write("big.ply", header + "end_header\n" + b.str());
  CHECK_THAT(read_points_error(ply), Contains(at_line(ply, 3)) && Contains("10000000"));

  const std::string ascii = tmp.write("big_ascii.ply",
                                      "ply\nformat ascii 1.0\nelement vertex 10000000\nproperty float x\n"
                                      "property float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n");
  CHECK_THAT(read_points_error(ascii), Contains(at_line(ascii, 3)) && Contains("10000000"));

  // Even a count that overflows any size computation.
  const std::string huge = tmp.write("huge.ply",
                                     "ply\nformat binary_big_endian 1.0\nelement vertex 9223372036854775807\n"
                                     "property double x\nproperty double y\nproperty double z\nend_header\n");
  CHECK_THAT(read_points_error(huge), Contains(at_line(huge, 3)));

  const std::string off = tmp.write("big.off", "OFF\n10000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  CHECK_THAT(read_mesh_error(off), Contains(at_line(off, 2)) && Contains("10000000"));

  const std::string pcd = tmp.write("big.pcd",
                                    "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                                    "WIDTH 10000000\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 10000000\n"
                                    "DATA ascii\n0 0 0\n1 0 0\n0 1 0\n");
  CHECK_THAT(read_points_error(pcd), Contains(pcd) && Contains("10000000"));
  Bytes p(false);
  for (int k = 0; k < 9; ++k) p.put(float(k));
  const std::string pcd_binary = tmp.write("big_binary.pcd",
                                           "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                                           "WIDTH 10000000\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 10000000\n"
                                           "DATA binary\n" + p.str());
  CHECK_THAT(read_points_error(pcd_binary), Contains(pcd_binary) && Contains("10000000"));
}

TEST_CASE("bad input: wrong OFF counts", "[io][bad]") {
  dtsl::test::TempDir tmp;
  // Long enough to pass the size check, so the counts are found wrong while reading.
  const std::string v3 = "0.000000 0.000000 0.000000\n1.000000 0.000000 0.000000\n0.000000 1.000000 0.000000\n";
  const std::string few_faces = tmp.write("a.off", "OFF\n3 2 0\n" + v3 + "3 0 1 2\n");
  CHECK_THAT(read_mesh_error(few_faces), Contains(at_line(few_faces, 6)) && Contains("1 of the 2 faces"));
  const std::string few_vertices = tmp.write("b.off", "OFF\n4 0 0\n" + v3);
  CHECK_THAT(read_points_error(few_vertices), Contains(at_line(few_vertices, 5)) && Contains("3 of the 4 vertices"));
  const std::string tiny = tmp.write("t.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  CHECK_THAT(read_mesh_error(tiny), Contains(at_line(tiny, 2)) && Contains("wrong counts"));
  const std::string extra = tmp.write("c.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 2 1 0\n");
  CHECK_THAT(read_mesh_error(extra), Contains(at_line(extra, 7)) && Contains("after the last face"));
  const std::string no_counts = tmp.write("d.off", "OFF\n# nothing else\n");
  CHECK_THAT(read_mesh_error(no_counts), Contains(no_counts) && Contains("counts"));
  const std::string corners = tmp.write("e.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n");
  CHECK_THAT(read_mesh_error(corners), Contains(at_line(corners, 6)) && Contains("announces 4"));
  const std::string index = tmp.write("f.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  CHECK_THAT(read_mesh_error(index), Contains(at_line(index, 6)) && Contains("vertex index 3 out of range"));
  const std::string header = tmp.write("g.off", "3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  CHECK_THAT(read_mesh_error(header), Contains(at_line(header, 1)) && Contains("'OFF'"));
}

TEST_CASE("bad input: OBJ indices zero or out of range", "[io][bad]") {
  dtsl::test::TempDir tmp;
  const std::string v3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const std::string zero = tmp.write("z.obj", v3 + "f 0 1 2\n");
  CHECK_THAT(read_mesh_error(zero), Contains(at_line(zero, 4)) && Contains("index 0"));
  const std::string high = tmp.write("h.obj", v3 + "# comment\nf 1 2 3\nf 1 2 4\n");
  CHECK_THAT(read_mesh_error(high), Contains(at_line(high, 6)) && Contains("vertex index 4 out of range"));
  const std::string negative = tmp.write("n.obj", v3 + "f -1 -2 -4\n");
  CHECK_THAT(read_mesh_error(negative), Contains(at_line(negative, 4)) && Contains("-4"));
  const std::string normal = tmp.write("vn.obj", v3 + "vn 0 0 1\nf 1//1 2//1 3//2\n");
  CHECK_THAT(read_mesh_error(normal), Contains(at_line(normal, 5)) && Contains("normal index 2 out of range"));
  const std::string two = tmp.write("two.obj", v3 + "f 1 2\n");
  CHECK_THAT(read_mesh_error(two), Contains(at_line(two, 4)) && Contains("at least 3"));
  const std::string slashes = tmp.write("s.obj", v3 + "f 1/1/1/1 2 3\n");
  CHECK_THAT(read_mesh_error(slashes), Contains(at_line(slashes, 4)) && Contains("'1/1/1/1'"));
}

TEST_CASE("bad input: PLY index out of range, in ascii and binary", "[io][bad]") {
  dtsl::test::TempDir tmp;
  const std::string ascii = tmp.write("a.ply",
                                      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                      "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                      "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n");
  CHECK_THAT(read_mesh_error(ascii), Contains(at_line(ascii, 13)) && Contains("vertex index -1 out of range"));
  Bytes b(false);
  for (int k = 0; k < 9; ++k) b.put(float(k));
  b.put(std::uint8_t{3}).put(0).put(1).put(3);
  const std::string binary =
      tmp.write("b.ply", std::string(kPlyXyzHeader) + "element face 1\nproperty list uchar int vertex_indices\n"
                                                      "end_header\n" + b.str());
  CHECK_THAT(read_mesh_error(binary), Contains(binary) && Contains("face 0 (of 1)") && Contains("vertex index 3"));
}

TEST_CASE("bad input: non-numeric tokens", "[io][bad]") {
  dtsl::test::TempDir tmp;
  const std::string obj = tmp.write("t.obj", "v 0 0 0\nv 1 abc 0\n");
  CHECK_THAT(read_points_error(obj), Contains(at_line(obj, 2)) && Contains("'abc'"));
  const std::string obj_face = tmp.write("f.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x3\n");
  CHECK_THAT(read_mesh_error(obj_face), Contains(at_line(obj_face, 4)) && Contains("'x3'"));
  const std::string xyz = tmp.write("t.xyz", "# header\n0 0 0\n1 0 0x1\n");
  CHECK_THAT(read_points_error(xyz), Contains(at_line(xyz, 3)) && Contains("'0x1'"));
  const std::string off = tmp.write("t.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1,5 0\n3 0 1 2\n");
  CHECK_THAT(read_mesh_error(off), Contains(at_line(off, 5)) && Contains("'1,5'"));
  const std::string ply = tmp.write("t.ply",
                                    "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                                    "property float z\nend_header\n0 0 0\n1 - 0\n");
  CHECK_THAT(read_points_error(ply), Contains(at_line(ply, 9)) && Contains("'-'"));
  const std::string count = tmp.write("c.off", "OFF\nthree 1 0\n");
  CHECK_THAT(read_mesh_error(count), Contains(at_line(count, 2)) && Contains("'three'"));
  const std::string xyz_columns = tmp.write("c.xyz", "0 0 0\n1 0 0 0 0 1\n");
  CHECK_THAT(read_points_error(xyz_columns), Contains(at_line(xyz_columns, 2)) && Contains("like line 1"));
  const std::string ply_type = tmp.write("ty.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty real x\n"
                                                   "end_header\n0\n");
  CHECK_THAT(read_points_error(ply_type), Contains(at_line(ply_type, 4)) && Contains("'real'"));
}

TEST_CASE("bad input: NaN or infinite coordinates are rejected on read", "[io][bad]") {
  dtsl::test::TempDir tmp;
  const std::string xyz = tmp.write("n.xyz", "0 0 0\n1 nan 0\n");
  CHECK_THAT(read_points_error(xyz), Contains(at_line(xyz, 2)) && Contains("NaN or infinite"));
  const std::string obj = tmp.write("n.obj", "v 0 0 0\nv inf 0 0\n");
  CHECK_THAT(read_points_error(obj), Contains(at_line(obj, 2)) && Contains("NaN or infinite"));
  const std::string overflow = tmp.write("o.xyz", "1e999 0 0\n");
  CHECK_THAT(read_points_error(overflow), Contains(at_line(overflow, 1)) && Contains("'1e999'"));
  const std::string off = tmp.write("n.off", "OFF\n3 1 0\n0 0 0\n1 0 -inf\n0 1 0\n3 0 1 2\n");
  CHECK_THAT(read_mesh_error(off), Contains(at_line(off, 4)) && Contains("NaN or infinite"));
  const std::string ply_ascii = tmp.write("a.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                                   "property float y\nproperty float z\nend_header\nNaN 0 0\n");
  CHECK_THAT(read_points_error(ply_ascii), Contains(at_line(ply_ascii, 8)) && Contains("NaN or infinite"));
  Bytes b(false);
  b.put(0.f).put(0.f).put(0.f).put(1.f).put(std::numeric_limits<float>::quiet_NaN()).put(0.f).put(0.f).put(1.f).put(0.f);
  const std::string ply = tmp.write("b.ply", std::string(kPlyXyzHeader) + "end_header\n" + b.str());
  CHECK_THAT(read_points_error(ply), Contains(ply) && Contains("vertex 1 (of 3)") && Contains("NaN or infinite"));
  const std::string pcd = tmp.write("n.pcd",
                                    "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\n"
                                    "HEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA ascii\n0 0 0\nnan nan nan\n");
  CHECK_THAT(read_points_error(pcd), Contains(pcd) && Contains("point 1") && Contains("NaN"));
}

TEST_CASE("bad input: read_mesh of a file without faces", "[io][bad]") {
  dtsl::test::TempDir tmp;
  const std::string off = tmp.write("p.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n");
  CHECK_THAT(read_mesh_error(off), Contains(off) && Contains("no faces"));
  REQUIRE(dtsl::read_points(off).size() == 3);  // but it is a fine point file
  const std::string obj = tmp.write("p.obj", "v 0 0 0\nv 1 0 0\n");
  CHECK_THAT(read_mesh_error(obj), Contains(obj) && Contains("no faces"));
  const std::string ply = tmp.write("p.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                             "property float y\nproperty float z\nend_header\n0 0 0\n");
  CHECK_THAT(read_mesh_error(ply), Contains(ply) && Contains("no faces"));
  const std::string xyz = tmp.write("p.xyz", "0 0 0\n");
  CHECK_THAT(read_mesh_error(xyz), Contains(xyz) && Contains("XYZ"));
  const std::string pcd = tmp.path("p.pcd");
  CHECK_THAT(read_mesh_error(pcd), Contains(pcd) && Contains("PCD"));
}

TEST_CASE("bad input: read_points of a file with zero points", "[io][bad]") {
  dtsl::test::TempDir tmp;
  const std::string xyz = tmp.write("z.xyz", "# only a comment\n\n");
  CHECK_THAT(read_points_error(xyz), Contains(xyz) && Contains("no points"));
  const std::string ply = tmp.write("z.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 0\n"
                                             "property float x\nproperty float y\nproperty float z\nend_header\n");
  CHECK_THAT(read_points_error(ply), Contains(ply) && Contains("no points"));
  const std::string obj = tmp.write("z.obj", "# nothing\n");
  CHECK_THAT(read_points_error(obj), Contains(obj) && Contains("no points"));
  const std::string off = tmp.write("z.off", "OFF 0 0 0\n");
  CHECK_THAT(read_points_error(off), Contains(off) && Contains("no points"));
  const std::string pcd = tmp.write("z.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                                             "WIDTH 0\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 0\nDATA ascii\n");
  CHECK_THAT(read_points_error(pcd), Contains(pcd) && Contains("no points"));
}

TEST_CASE("bad input: malformed PLY headers", "[io][bad]") {
  dtsl::test::TempDir tmp;
  const std::string magic = tmp.write("m.ply", "PLY\nformat ascii 1.0\nend_header\n");
  CHECK_THAT(read_points_error(magic), Contains(at_line(magic, 1)) && Contains("not a PLY file"));
  const std::string no_end = tmp.write("e.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n");
  CHECK_THAT(read_points_error(no_end), Contains(no_end) && Contains("end_header"));
  const std::string no_z = tmp.write("z.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                              "property float y\nend_header\n0 0\n");
  CHECK_THAT(read_points_error(no_z), Contains(at_line(no_z, 3)) && Contains("'z'"));
  const std::string format = tmp.write("f.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n");
  CHECK_THAT(read_points_error(format), Contains(at_line(format, 2)) && Contains("binary_middle_endian"));
  const std::string extra = tmp.write("x.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                               "property float y\nproperty float z\nend_header\n0 0 0\n1 1 1\n");
  CHECK_THAT(read_points_error(extra), Contains(at_line(extra, 9)) && Contains("after the last element"));
  const std::string float_index = tmp.write("fi.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"
                                                      "property float y\nproperty float z\nelement face 0\n"
                                                      "property list uchar float vertex_indices\nend_header\n");
  CHECK_THAT(read_mesh_error(float_index), Contains(at_line(float_index, 7)) && Contains("integers"));
}

TEST_CASE("bad input: writing a mesh as XYZ or PCD names the format and writes nothing", "[io][bad]") {
  dtsl::test::TempDir tmp;
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  m.faces = {{0, 1, 2}};
  const std::string xyz = tmp.path("m.xyz");
  CHECK_THAT(file_error([&] { dtsl::write_mesh(xyz, m); }), Contains(xyz) && Contains("XYZ"));
  const std::string pcd = tmp.path("m.pcd");
  CHECK_THAT(file_error([&] { dtsl::write_mesh(pcd, m); }), Contains(pcd) && Contains("PCD"));
  REQUIRE(std::filesystem::is_empty(tmp.dir()));
}

TEST_CASE("bad input: writes that fail leave no file behind and keep the old one", "[io][bad]") {
  dtsl::test::TempDir tmp;
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  m.faces = {{0, 1, 2}};
  const std::string path = tmp.path("m.ply");
  dtsl::write_mesh(path, m);
  TriangleMesh bad = m;
  bad.faces.push_back({0, 1, 3});
  CHECK_THAT(file_error([&] { dtsl::write_mesh(path, bad); }), Contains(path) && Contains("face 1"));
  bad = m;
  bad.vertices[1].x() = std::numeric_limits<double>::quiet_NaN();
  CHECK_THAT(file_error([&] { dtsl::write_mesh(path, bad); }), Contains(path) && Contains("vertex 1"));
  REQUIRE(dtsl::read_mesh(path).vertices == m.vertices);  // untouched
  const std::string nowhere = tmp.path("missing/dir/m.off");
  CHECK_THAT(file_error([&] { dtsl::write_mesh(nowhere, m); }), Contains(nowhere));
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(tmp.dir())) {
    (void)e;
    ++files;
  }
  REQUIRE(files == 1);
}
