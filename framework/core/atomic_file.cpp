#include "framework/core/atomic_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "framework/core/error.hpp"

namespace dtsl {

std::string temporary_path_for(const std::string& path) {
  return path + ".tmp-" + std::to_string(::getpid());
}

void commit_temporary(const std::string& temporary, const std::string& path) {
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(temporary.c_str());
    throw FileError(path, "cannot write: " + why);
  }
}

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::string tmp = temporary_path_for(path);
  try {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw FileError(path, std::string("cannot open for writing: ") + std::strerror(errno));
    write(out);
    out.flush();
    if (!out) throw FileError(path, "write failed (disk full?)");
    out.close();
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
  commit_temporary(tmp, path);
}

}  // namespace dtsl
