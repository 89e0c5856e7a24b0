// The allocator's tuning (framework/core/allocator.hpp): freed heap memory stays mapped, so the next
// evolution step's least-squares system does not fault its pages in again.
#include <cstdlib>
#include <vector>

#include <catch2/catch.hpp>

#include "framework/core/allocator.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

// AddressSanitizer brings its own allocator: mallopt() refuses every setting (returns 0) there.
#if defined(__SANITIZE_ADDRESS__)
#define DTSL_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define DTSL_TEST_ASAN 1
#endif
#endif

using namespace dtsl;

TEST_CASE("configure_allocator keeps freed heap memory mapped and says what it did", "[allocator]") {
#if defined(DTSL_TEST_ASAN)
  unsetenv("MALLOC_TOP_PAD_");
  CHECK(configure_allocator(64) == "glibc defaults (mallopt refused M_TOP_PAD)");
  CHECK(allocator_configuration() == "glibc defaults (mallopt refused M_TOP_PAD)");
#elif defined(__GLIBC__)
  unsetenv("MALLOC_TOP_PAD_");
  CHECK(configure_allocator(0) == "glibc defaults");
  CHECK(allocator_configuration() == "glibc defaults");
  REQUIRE(configure_allocator(64) == "glibc, M_TOP_PAD 64 MiB");
  CHECK(allocator_configuration() == "glibc, M_TOP_PAD 64 MiB");
  // 32 MiB in blocks below the mmap threshold, i.e. from the heap, then all freed: with the pad the
  // heap keeps them instead of trimming back to what it held before.
  std::vector<void*> blocks;
  for (int k = 0; k < 512; ++k) blocks.push_back(std::malloc(64 * 1024));
  for (void* b : blocks) std::free(b);
  CHECK(mallinfo2().arena >= std::size_t(32) * 1024 * 1024);

  setenv("MALLOC_TOP_PAD_", "1048576", 1);
  CHECK(configure_allocator(64) == "glibc, MALLOC_TOP_PAD_ from the environment");
  unsetenv("MALLOC_TOP_PAD_");
  CHECK(configure_allocator(100000) == "glibc, M_TOP_PAD 2047 MiB");  // mallopt takes an int of bytes
  configure_allocator(0);
#else
  CHECK(configure_allocator(64) == "the C library's defaults");
#endif
}
