// libFuzzer target: binary PLY bodies. The first input byte picks one of a few fixed headers (both
// endiannesses, normals, list count and index types, an extra element with a list to skip) and the
// rest is the body, so the fuzzer spends its time on the element decoding rather than on the header
// grammar (fuzz_ply covers that).
#include <cstddef>
#include <cstdint>
#include <string>

#include "framework/core/error.hpp"
#include "framework/io/formats.hpp"
#include "fuzz/fuzz_support.hpp"

namespace {

const char* const kHeaders[] = {
    "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n",
    "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
    "property double z\nproperty double nx\nproperty double ny\nproperty double nz\nend_header\n",
    "ply\nformat binary_little_endian 1.0\nelement vertex 5\nproperty uchar red\nproperty float x\n"
    "property float y\nproperty float z\nproperty list int float junk\nelement face 3\n"
    "property list ushort uint vertex_index\nproperty int flags\nend_header\n",
    "ply\nformat binary_little_endian 1.0\nelement extra 2\nproperty list uint uchar stuff\n"
    "element vertex 3\nproperty short x\nproperty short y\nproperty short z\nelement face 1\n"
    "property list char short vertex_indices\nend_header\n",
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t n = sizeof kHeaders / sizeof kHeaders[0];
  std::string file = kHeaders[data[0] % n];
  file.append(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    dtsl::fuzz::check_mesh(dtsl::io_detail::read_ply("fuzz.ply", file));
  } catch (const dtsl::Error&) {
  }
  return 0;
}
