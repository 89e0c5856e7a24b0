// XYZ: one point per line, "x y z" or "x y z nx ny nz" (the same for every line); blank lines and '#'
// comments are allowed.
#include <string>
#include <string_view>

#include "framework/core/atomic_file.hpp"
#include "framework/core/error.hpp"
#include "framework/io/formats.hpp"
#include "framework/io/text_lines.hpp"
#include "framework/io/text_writer.hpp"

namespace dtsl::io_detail {

TriangleMesh read_xyz(const std::string& path, std::string_view text) {
  LineReader in(path, text);
  TriangleMesh cloud;
  std::size_t per_line = 0;
  long first_line = 0;
  while (in.next()) {
    Tokens tok(strip_comment(in.line()));
    const std::size_t n = tok.count();
    if (n == 0) continue;
    if (n != 3 && n != 6) in.fail("expected 3 numbers (x y z) or 6 (x y z nx ny nz), got " + std::to_string(n));
    if (per_line == 0) {
      per_line = n;
      first_line = in.number();
    } else if (n != per_line) {
      in.fail("expected " + std::to_string(per_line) + " numbers like line " + std::to_string(first_line) +
              ", got " + std::to_string(n));
    }
    double c[6];
    std::string_view t;
    for (std::size_t j = 0; j < n; ++j) {
      tok.next(t);
      c[j] = parse_double(in, t, j < 3 ? "a coordinate" : "a normal coordinate");
    }
    cloud.vertices.emplace_back(c[0], c[1], c[2]);
    if (n == 6) cloud.normals.emplace_back(c[3], c[4], c[5]);
  }
  return cloud;
}

void write_xyz(const std::string& path, const std::vector<Vec3>& points, const std::vector<Vec3>& normals) {
  write_file_atomically(path, [&](std::ostream& out) {
    std::string buf;
    for (std::size_t i = 0; i < points.size(); ++i) {
      append_point_line(buf, points[i], normals.empty() ? nullptr : &normals[i]);
      flush_if_large(out, buf);
    }
    flush_if_large(out, buf, true);
  });
}

}  // namespace dtsl::io_detail
