#include "framework/core/allocator.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

// Sanitizers replace malloc: mallopt() is refused (ASan, LSan) or ignored (TSan) there.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define DTSL_SANITIZER_ALLOCATOR 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define DTSL_SANITIZER_ALLOCATOR 1
#endif
#endif

namespace dtsl {

namespace {

std::string& configuration() {
  static std::string text = "not configured";
  return text;
}

std::string configure(long top_pad_mib) {
  const char* choice = std::getenv("DTSL_ALLOCATOR");
  if (choice && std::strcmp(choice, "default") == 0) return "the C library's defaults (DTSL_ALLOCATOR=default)";
#if defined(DTSL_SANITIZER_ALLOCATOR)
  (void)top_pad_mib;
  return "the sanitizer's allocator (not configured)";
#elif defined(__GLIBC__)
  if (std::getenv("MALLOC_TOP_PAD_")) return "glibc, MALLOC_TOP_PAD_ from the environment";
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables && std::strstr(tunables, "glibc.malloc.top_pad")) return "glibc, top_pad from GLIBC_TUNABLES";
  if (top_pad_mib <= 0) return "glibc, not changed";
  const long mib = std::min(top_pad_mib, 2047L);  // mallopt takes an int of bytes
  if (mallopt(M_TOP_PAD, int(mib * 1024 * 1024)) != 1) return "glibc, not changed (mallopt refused M_TOP_PAD)";
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
