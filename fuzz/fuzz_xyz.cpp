// libFuzzer target: the XYZ reader on arbitrary bytes (fuzz/README.md).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "framework/core/error.hpp"
#include "framework/io/formats.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    dtsl::fuzz::check_mesh(dtsl::io_detail::read_xyz("fuzz.xyz", text));
  } catch (const dtsl::Error&) {
    // a clear rejection: expected
  }
  return 0;
}
