// Private to framework/io: loading a whole input file into memory. Readers parse from one buffer
// because it is fast (one read, no stream per token) and because its size bounds every count a header
// may claim. Header-only so that the PCD target (which cannot link dtsl_io) can share the checks.
#pragma once

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "framework/core/error.hpp"

namespace dtsl::io_detail {

/// Size of the file at `path`. FileError if it is missing, not a regular file (a FIFO or a device
/// could block forever) or empty.
inline std::size_t checked_file_size(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw FileError(path, std::string("cannot open: ") + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw FileError(path, "not a regular file");
  if (st.st_size == 0) throw FileError(path, "file is empty");
  return static_cast<std::size_t>(st.st_size);
}

/// The whole content of the regular file at `path` (same errors as checked_file_size).
inline std::string load_file(const std::string& path) {
  const std::size_t size = checked_file_size(path);
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw FileError(path, std::string("cannot open: ") + std::strerror(errno));
  std::string data(size, '\0');
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::read(fd, &data[done], size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const std::string why = std::strerror(errno);
      ::close(fd);
      throw FileError(path, "cannot read: " + why);
    }
    if (n == 0) break;  // the file shrank while we read it: parse what is there
    done += static_cast<std::size_t>(n);
  }
  ::close(fd);
  data.resize(done);
  if (data.empty()) throw FileError(path, "file is empty");
  return data;
}

}  // namespace dtsl::io_detail
