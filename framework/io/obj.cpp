// Wavefront OBJ: v, vn and f records. Face corners may be v, v/vt, v//vn or v/vt/vn with 1-based or
// negative (relative to the vertices defined so far) indices; polygons are fan-triangulated. Other
// records (vt, groups, materials, lines, free-form geometry) carry nothing a TriangleMesh holds and
// are ignored.
#include <array>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "framework/core/atomic_file.hpp"
#include "framework/core/error.hpp"
#include "framework/io/formats.hpp"
#include "framework/io/text_lines.hpp"
#include "framework/io/text_writer.hpp"

namespace dtsl::io_detail {
namespace {

// OBJ allows an index to refer to an element defined later in the file, so positive indices are
// checked once the whole file is read; the largest one and its line are enough to report the error.
struct IndexCheck {
  long long largest = -1;
  long line = 0;

  void note(long long index, long at) {
    if (index > largest) {
      largest = index;
      line = at;
    }
  }
  void verify(const std::string& path, std::size_t count, const char* what, const char* plural) const {
    if (largest >= static_cast<long long>(count))
      throw FileError(path, std::string(what) + " " + std::to_string(largest + 1) + " out of range (the file has " +
                                std::to_string(count) + " " + plural + ")", line);
  }
};

// Resolves a 1-based or negative OBJ index to a 0-based one.
int resolve(const LineReader& in, std::string_view token, std::size_t defined, const char* what,
            IndexCheck& check) {
  const long long i = parse_integer(in, token, what);
  if (i == 0) in.fail(std::string(what) + " 0 is invalid (OBJ indices start at 1)");
  if (i < 0) {
    const long long r = static_cast<long long>(defined) + i;
    if (r < 0)
      in.fail("relative " + std::string(what) + " " + std::to_string(i) + " out of range (only " +
              std::to_string(defined) + " defined before this line)");
    return static_cast<int>(r);
  }
  if (i > std::numeric_limits<int>::max()) in.fail(std::string(what) + " " + std::to_string(i) + " out of range");
  check.note(i - 1, in.number());
  return static_cast<int>(i - 1);
}

}  // namespace

TriangleMesh read_obj(const std::string& path, std::string_view text) {
  LineReader in(path, text);
  TriangleMesh mesh;
  std::vector<Vec3> normals;
  std::vector<std::array<int, 3>> face_normals;  // per triangle, -1 where a corner has no normal
  bool faces_have_normals = false;
  IndexCheck vertex_check, normal_check;
  std::vector<int> corners, corner_normals;

  while (in.next()) {
    Tokens tok(strip_comment(in.line()));
    std::string_view word, t;
    if (!tok.next(word)) continue;
    if (word == "v") {
      double c[3] = {0, 0, 0};
      int n = 0;
      for (; tok.next(t); ++n) {  // x y z, then an optional w or r g b: all must be numbers
        const double x = parse_double(in, t, "a vertex coordinate");
        if (n < 3) c[n] = x;
      }
      if (n < 3) in.fail("a vertex needs 3 coordinates, got " + std::to_string(n));
      mesh.vertices.emplace_back(c[0], c[1], c[2]);
    } else if (word == "vn") {
      double c[3] = {0, 0, 0};
      int n = 0;
      for (; tok.next(t); ++n) {
        if (n == 3) in.fail("a normal has 3 coordinates, got more");
        c[n] = parse_double(in, t, "a normal coordinate");
      }
      if (n < 3) in.fail("a normal needs 3 coordinates, got " + std::to_string(n));
      normals.emplace_back(c[0], c[1], c[2]);
    } else if (word == "f") {
      corners.clear();
      corner_normals.clear();
      while (tok.next(t)) {
        std::string_view part[3];
        int parts = 0;
        for (std::size_t start = 0;;) {
          const std::size_t slash = t.find('/', start);
          if (parts == 3) in.fail("malformed face corner " + quoted(t) + " (expected v, v/vt, v//vn or v/vt/vn)");
          part[parts++] = t.substr(start, slash == std::string_view::npos ? std::string_view::npos : slash - start);
          if (slash == std::string_view::npos) break;
          start = slash + 1;
        }
        if (part[0].empty()) in.fail("malformed face corner " + quoted(t) + " (no vertex index)");
        corners.push_back(resolve(in, part[0], mesh.vertices.size(), "vertex index", vertex_check));
        if (parts >= 2 && !part[1].empty()) {
          // Texture coordinates are not kept, but the index must still be a valid number.
          if (parse_integer(in, part[1], "texture index") == 0)
            in.fail("texture index 0 is invalid (OBJ indices start at 1)");
        }
        if (parts == 3 && !part[2].empty())
          corner_normals.push_back(resolve(in, part[2], normals.size(), "normal index", normal_check));
        else
          corner_normals.push_back(-1);
      }
      if (corners.size() < 3) in.fail("a face needs at least 3 vertices, got " + std::to_string(corners.size()));
      for (std::size_t j = 1; j + 1 < corners.size(); ++j) {
        mesh.faces.push_back({corners[0], corners[j], corners[j + 1]});
        face_normals.push_back({corner_normals[0], corner_normals[j], corner_normals[j + 1]});
        faces_have_normals = faces_have_normals || corner_normals[0] >= 0 || corner_normals[j] >= 0 ||
                             corner_normals[j + 1] >= 0;
      }
    }
  }
  vertex_check.verify(path, mesh.vertices.size(), "vertex index", "vertices");
  normal_check.verify(path, normals.size(), "normal index", "normals");

  // Per-vertex normals: from the face corners if they give every vertex one, else (a point cloud
  // written as v/vn pairs) one vn per v.
  if (faces_have_normals) {
    std::vector<int> of_vertex(mesh.vertices.size(), -1);
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
      for (int c = 0; c < 3; ++c)
        if (face_normals[f][c] >= 0) of_vertex[mesh.faces[f][c]] = face_normals[f][c];
    bool complete = true;
    for (int n : of_vertex) complete = complete && n >= 0;
    if (complete) {
      mesh.normals.reserve(of_vertex.size());
      for (int n : of_vertex) mesh.normals.push_back(normals[n]);
    }
  } else if (!normals.empty() && normals.size() == mesh.vertices.size()) {
    mesh.normals = std::move(normals);
  }
  return mesh;
}

void write_obj(const std::string& path, const std::vector<Vec3>& vertices, const std::vector<Vec3>& normals,
               const std::vector<Face>& faces) {
  write_file_atomically(path, [&](std::ostream& out) {
    std::string buf = "# written by dtsl\n";
    const auto put3 = [&](const char* tag, const Vec3& p) {
      buf += tag;
      for (int c = 0; c < 3; ++c) {
        buf += ' ';
        append_number(buf, p[c]);
      }
      buf += '\n';
      flush_if_large(out, buf);
    };
    for (const Vec3& p : vertices) put3("v", p);
    for (const Vec3& n : normals) put3("vn", n);
    for (const Face& f : faces) {
      buf += 'f';
      for (int c = 0; c < 3; ++c) {
        buf += ' ';
        append_number(buf, static_cast<long long>(f[c]) + 1);
        if (!normals.empty()) {
          buf += "//";
          append_number(buf, static_cast<long long>(f[c]) + 1);
        }
      }
      buf += '\n';
      flush_if_large(out, buf);
    }
    flush_if_large(out, buf, true);
  });
}

}  // namespace dtsl::io_detail
