// Geomview OFF: an 'OFF' keyword (optionally ST/C/N-prefixed: texture coordinates, colours and normals
// per vertex), the counts "nv nf ne" on the same line or the next, then one vertex per line and one
// polygon per line ("k i1 ... ik [colour]"); '#' starts a comment. Polygons are fan-triangulated. The
// header's counts are checked both ways: a file that ends early or holds more than it announced is
// rejected, since either means the counts cannot be trusted.
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

// Moves to the next line that is not blank once comments are removed.
bool next_content(LineReader& in) {
  while (in.next())
    if (!is_blank(strip_comment(in.line()))) return true;
  return false;
}

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }

}  // namespace

TriangleMesh read_off(const std::string& path, std::string_view text) {
  LineReader in(path, text);
  if (!next_content(in)) throw FileError(path, "not an OFF file: it holds only comments and blank lines");

  Tokens tok(strip_comment(in.line()));
  std::string_view word;
  tok.next(word);
  std::string_view k = word;
  if (starts_with(k, "ST")) k.remove_prefix(2);
  if (starts_with(k, "C")) k.remove_prefix(1);
  const bool has_normals = starts_with(k, "N");
  if (has_normals) k.remove_prefix(1);
  if (k == "4OFF" || k == "nOFF" || k == "4nOFF")
    in.fail("unsupported OFF variant " + quoted(word) + " (only 3-dimensional vertices are read)");
  if (k != "OFF") in.fail("not an OFF file: expected the keyword 'OFF' on the first line, got " + quoted(word));

  if (tok.count() == 0) {  // the counts are on the next line
    if (!next_content(in)) throw FileError(path, "the file ends before the OFF counts", in.number());
    tok = Tokens(strip_comment(in.line()));
  }
  std::string_view t;
  long long count[3] = {0, 0, 0};
  int ncounts = 0;
  while (tok.next(t)) {
    if (t == "BINARY") in.fail("binary OFF files are not supported");
    if (ncounts == 3) in.fail("expected the counts 'vertices faces edges', got more than 3 numbers");
    count[ncounts++] = parse_integer(in, t, "a count");
  }
  if (ncounts < 2) in.fail("expected the counts 'vertices faces [edges]'");
  const long long nv = count[0], nf = count[1];
  if (nv < 0 || nf < 0) in.fail("negative vertex or face count");
  if (nv > std::numeric_limits<int>::max()) in.fail("too many vertices (" + std::to_string(nv) + ")");

  // Before allocating: "x y z\n" and "3 i j k\n" are the shortest vertex and face lines.
  const std::size_t available = text.size() - in.end_offset();
  const unsigned __int128 needed = static_cast<unsigned __int128>(nv) * 6 + static_cast<unsigned __int128>(nf) * 8;
  if (needed > static_cast<unsigned __int128>(available) + 1)
    in.fail("header promises " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
            " faces, but only " + std::to_string(available) + " bytes follow it (truncated file or wrong counts?)");

  TriangleMesh mesh;
  mesh.vertices.reserve(static_cast<std::size_t>(nv));
  if (has_normals) mesh.normals.reserve(static_cast<std::size_t>(nv));
  mesh.faces.reserve(static_cast<std::size_t>(nf));
  const std::size_t values = has_normals ? 6 : 3;
  for (long long i = 0; i < nv; ++i) {
    if (!next_content(in))
      throw FileError(path, "the file ends after " + std::to_string(i) + " of the " + std::to_string(nv) +
                                " vertices its header promises", in.number());
    Tokens v(strip_comment(in.line()));
    if (v.count() < values)
      in.fail("vertex " + std::to_string(i) + " needs " + std::to_string(values) + " numbers, got " +
              std::to_string(v.count()));
    double c[6];
    for (std::size_t j = 0; j < values; ++j) {
      v.next(t);
      c[j] = parse_double(in, t, j < 3 ? "a vertex coordinate" : "a normal coordinate");
    }
    mesh.vertices.emplace_back(c[0], c[1], c[2]);
    if (has_normals) mesh.normals.emplace_back(c[3], c[4], c[5]);
    // Anything after (colour, texture coordinates) is not kept.
  }

  std::vector<int> corners;
  for (long long f = 0; f < nf; ++f) {
    if (!next_content(in))
      throw FileError(path, "the file ends after " + std::to_string(f) + " of the " + std::to_string(nf) +
                                " faces its header promises", in.number());
    Tokens p(strip_comment(in.line()));
    p.next(t);
    const long long n = parse_integer(in, t, "the number of face vertices");
    if (n < 3) in.fail("face " + std::to_string(f) + " needs at least 3 vertices, got " + std::to_string(n));
    if (static_cast<unsigned long long>(n) > p.count())
      in.fail("face " + std::to_string(f) + " announces " + std::to_string(n) + " vertices but lists " +
              std::to_string(p.count()));
    corners.clear();
    for (long long j = 0; j < n; ++j) {
      p.next(t);
      const long long idx = parse_integer(in, t, "a vertex index");
      if (idx < 0 || idx >= nv)
        in.fail("vertex index " + std::to_string(idx) + " out of range (the file has " + std::to_string(nv) +
                " vertices)");
      corners.push_back(static_cast<int>(idx));
    }
    for (std::size_t j = 1; j + 1 < corners.size(); ++j) mesh.faces.push_back({corners[0], corners[j], corners[j + 1]});
  }
  if (next_content(in))
    in.fail("unexpected data after the last face (the header promises " + std::to_string(nv) + " vertices and " +
            std::to_string(nf) + " faces)");
  return mesh;
}

void write_off(const std::string& path, const std::vector<Vec3>& vertices, const std::vector<Vec3>& normals,
               const std::vector<Face>& faces) {
  write_file_atomically(path, [&](std::ostream& out) {
    // NOFF (normals after each vertex's coordinates) keeps vertex normals through a round trip.
    std::string buf = normals.empty() ? "OFF\n" : "NOFF\n";
    buf += std::to_string(vertices.size()) + " " + std::to_string(faces.size()) + " 0\n";
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      append_point_line(buf, vertices[i], normals.empty() ? nullptr : &normals[i]);
      flush_if_large(out, buf);
    }
    for (const Face& f : faces) {
      buf += '3';
      for (int c = 0; c < 3; ++c) {
        buf += ' ';
        append_number(buf, static_cast<long long>(f[c]));
      }
      buf += '\n';
      flush_if_large(out, buf);
    }
    flush_if_large(out, buf, true);
  });
}

}  // namespace dtsl::io_detail
