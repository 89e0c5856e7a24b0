// Private to framework/io: building text output in a string. Doubles are written in the shortest form
// that reads back to the same value (std::to_chars), so text round trips are exact.
#pragma once

#include <charconv>
#include <ostream>
#include <string>

#include "framework/core/types.hpp"

namespace dtsl::io_detail {

inline void append_number(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

inline void append_number(std::string& out, long long v) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

/// Sends `buffer` to `out` once it holds more than about 1 MiB, so writing a large mesh needs little
/// memory beyond the mesh itself.
/// "x y z[ nx ny nz]\n": one point line of the OFF and XYZ writers.
inline void append_point_line(std::string& out, const Vec3& p, const Vec3* normal) {
  for (int c = 0; c < 3; ++c) {
    if (c > 0) out += ' ';
    append_number(out, p[c]);
  }
  if (normal)
    for (int c = 0; c < 3; ++c) {
      out += ' ';
      append_number(out, (*normal)[c]);
    }
  out += '\n';
}

inline void flush_if_large(std::ostream& out, std::string& buffer, bool force = false) {
  if (force || buffer.size() > (1u << 20)) {
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    buffer.clear();
  }
}

}  // namespace dtsl::io_detail
