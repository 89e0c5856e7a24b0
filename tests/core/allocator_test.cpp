// The allocator's tuning (framework/core/allocator.hpp): freed heap memory stays mapped, so the next
// evolution step's least-squares system does not fault its pages in again.
#include <cstdlib>
#include <vector>

#include <catch2/catch.hpp>

#include "framework/core/allocator.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

// Sanitizers bring their own allocator, which mallopt() does not configure.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define DTSL_TEST_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define DTSL_TEST_SANITIZER 1
#endif
#endif

using namespace dtsl;

TEST_CASE("configure_allocator keeps freed heap memory mapped and says what it did", "[allocator]") {
  unsetenv("MALLOC_TOP_PAD_");
  unsetenv("DTSL_ALLOCATOR");
  setenv("DTSL_ALLOCATOR", "default", 1);
  CHECK(configure_allocator(64) == "the C library's defaults (DTSL_ALLOCATOR=default)");
  CHECK(allocator_configuration() == "the C library's defaults (DTSL_ALLOCATOR=default)");
  unsetenv("DTSL_ALLOCATOR");
#if defined(DTSL_TEST_SANITIZER)
  CHECK(configure_allocator(64) == "the sanitizer's allocator (not configured)");
#elif defined(__GLIBC__)
  CHECK(configure_allocator(0) == "glibc, not changed");
  REQUIRE(configure_allocator(64) == "glibc, M_TOP_PAD 64 MiB");
  CHECK(allocator_configuration() == "glibc, M_TOP_PAD 64 MiB");
  // 32 MiB in blocks below the mmap threshold, i.e. from the heap, then all freed: with the pad the
  // heap keeps them instead of trimming back to what it held before (without it this check fails).
  std::vector<void*> blocks;
  for (int k = 0; k < 512; ++k) blocks.push_back(std::malloc(64 * 1024));
  for (void* b : blocks) std::free(b);
  CHECK(mallinfo2().arena >= std::size_t(32) * 1024 * 1024);

  setenv("MALLOC_TOP_PAD_", "1048576", 1);
  CHECK(configure_allocator(64) == "glibc, MALLOC_TOP_PAD_ from the environment");
  unsetenv("MALLOC_TOP_PAD_");
  CHECK(configure_allocator(100000) == "glibc, M_TOP_PAD 2047 MiB");  // mallopt takes an int of bytes
  mallopt(M_TOP_PAD, 128 * 1024);  // glibc's default again, for the rest of this test binary
#else
  CHECK(configure_allocator(64) == "the C library's defaults");
#endif
}
