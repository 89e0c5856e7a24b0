// libFuzzer target: the PCD reader (our validation, then PCL's decoder) on arbitrary bytes. PCL reads
// from a file name, so each input is written to a private temporary file first.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "framework/core/error.hpp"
#include "framework/io/pcd_io.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/dtsl_fuzz_pcd_" + std::to_string(::getpid()) + ".pcd";
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) __builtin_trap();
  if (size && std::fwrite(data, 1, size, f) != size) __builtin_trap();
  std::fclose(f);
  try {
    dtsl::PointCloud cloud = dtsl::io_detail::read_pcd(path);
    dtsl::TriangleMesh m;
    m.vertices = std::move(cloud.points);
    m.normals = std::move(cloud.normals);
    dtsl::fuzz::check_mesh(m);
  } catch (const dtsl::Error&) {
  }
  std::remove(path.c_str());
  return 0;
}
