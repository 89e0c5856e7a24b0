// Process-wide tuning of the C library's allocator, called once by `dtsl`'s and the benches' main(),
// before any thread starts.
#pragma once

#include <string>

namespace dtsl {

/// Keeps up to `top_pad_mib` of freed heap memory mapped instead of handing it back to the kernel
/// (glibc's M_TOP_PAD). Every evolution step builds and drops least-squares systems of tens to hundreds
/// of MB; with glibc's defaults each step faulted its pages in afresh, and the page faults (serialised
/// between the OpenMP threads, and dear in a virtual machine) were up to a quarter of the wall time
/// (the timings: docs/performance.md, "What keeps it fast"). Meshes do not change. Side effect: glibc then stops adapting its mmap threshold, so blocks of
/// 128 KiB or more that do not fit the retained heap are mmapped each time.
///
/// Left alone (and said so) when DTSL_ALLOCATOR=default is in the environment (for A/B timings against
/// glibc's defaults), when the user set MALLOC_TOP_PAD_ or glibc.malloc.top_pad in GLIBC_TUNABLES, when
/// top_pad_mib <= 0, under a sanitizer (its own allocator ignores mallopt), or without glibc. Returns
/// what was done; not thread-safe (call it first thing in main()).
std::string configure_allocator(long top_pad_mib = 256);

/// What the last configure_allocator() did ("not configured" before any call), for a run's provenance.
std::string allocator_configuration();

}  // namespace dtsl
