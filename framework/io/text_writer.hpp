// Private to framework/io: building text output in a string. Doubles are written in the shortest form
// that reads back to the same value (std::to_chars), so text round trips are exact.
#pragma once

#include <charconv>
#include <ostream>
#include <string>

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
inline void flush_if_large(std::ostream& out, std::string& buffer, bool force = false) {
  if (force || buffer.size() > (1u << 20)) {
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    buffer.clear();
  }
}

}  // namespace dtsl::io_detail
