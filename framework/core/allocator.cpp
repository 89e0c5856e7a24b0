#include "framework/core/allocator.hpp"

#include <algorithm>
#include <cstdlib>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace dtsl {

namespace {

std::string& configuration() {
  static std::string text = "not configured";
  return text;
}

std::string configure(long top_pad_mib) {
#if defined(__GLIBC__)
  if (std::getenv("MALLOC_TOP_PAD_")) return "glibc, MALLOC_TOP_PAD_ from the environment";
  if (top_pad_mib <= 0) return "glibc defaults";
  const long mib = std::min(top_pad_mib, 2047L);  // mallopt takes an int of bytes
  if (mallopt(M_TOP_PAD, int(mib * 1024 * 1024)) != 1) return "glibc defaults (mallopt refused M_TOP_PAD)";
  return "glibc, M_TOP_PAD " + std::to_string(mib) + " MiB";
#else
  (void)top_pad_mib;
  return "the C library's defaults";
#endif
}

}  // namespace

std::string configure_allocator(long top_pad_mib) { return configuration() = configure(top_pad_mib); }

std::string allocator_configuration() { return configuration(); }

}  // namespace dtsl
