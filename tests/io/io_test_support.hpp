// Helpers shared by the io tests: a scratch folder under /tmp, file writing, catching a FileError's
// message, and a byte builder for binary PLY bodies of any type and byte order.
#pragma once

#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "framework/core/error.hpp"

namespace dtsl::test {

/// A fresh folder under /tmp, removed with everything in it when the object goes.
class TempDir {
 public:
  TempDir() {
    char pattern[] = "/tmp/dtsl-io-test-XXXXXX";
    const char* made = ::mkdtemp(pattern);
    REQUIRE(made != nullptr);
    dir_ = made;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::string path(const std::string& name) const { return dir_ + "/" + name; }
  /// Writes `bytes` to a file named `name` in the folder and returns its path.
  std::string write(const std::string& name, const std::string& bytes) const {
    const std::string p = path(name);
    std::ofstream out(p, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    REQUIRE(out.good());
    return p;
  }
  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
};

/// The message of the FileError `f` throws; fails the test if it throws anything else or nothing.
inline std::string file_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const FileError& e) {
    return e.what();
  } catch (const std::exception& e) {
    FAIL("expected a FileError, got: " << e.what());
  }
  FAIL("expected a FileError, nothing was thrown");
  return "";
}

inline std::string data_path(const std::string& name) { return std::string(DTSL_TEST_DATA_DIR) + "/io/" + name; }

/// Appends values in a chosen byte order, for hand-made binary PLY bodies.
class Bytes {
 public:
  explicit Bytes(bool big_endian) : big_(big_endian) {}
  template <class T>
  Bytes& put(T v) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    const bool host_big = __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__;
    if (big_ != host_big)
      for (std::size_t k = 0; k < sizeof(T) / 2; ++k) std::swap(b[k], b[sizeof(T) - 1 - k]);
    data_.append(reinterpret_cast<const char*>(b), sizeof(T));
    return *this;
  }
  const std::string& str() const { return data_; }

 private:
  bool big_;
  std::string data_;
};

}  // namespace dtsl::test
