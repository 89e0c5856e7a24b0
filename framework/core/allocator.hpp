// Process-wide tuning of the C library's allocator, called once by each executable's main().
#pragma once

#include <string>

namespace dtsl {

/// Keeps up to `top_pad_mib` of freed heap memory mapped instead of handing it back to the kernel
/// (glibc's M_TOP_PAD). Every evolution step builds and drops least-squares systems of tens to hundreds
/// of MB; with glibc's defaults each step faulted its pages in afresh, and the page faults (serialised
/// between the OpenMP threads, and dear in a virtual machine) were up to a quarter of the wall time.
/// `bench/compare_builds.sh` (3 alternating runs, 2 threads), together with the rows' reservations in
/// least_squares_rows.cpp: fandisk 8.22 -> 5.86 s, the 25k armadillo 22.4 -> 18.8 s, meshes identical.
/// A user's own MALLOC_TOP_PAD_ in the environment wins; 0 leaves the allocator alone. Returns what was
/// done; without glibc it does nothing and says so.
std::string configure_allocator(long top_pad_mib = 256);

/// What the last configure_allocator() did ("not configured" before any call), for a run's provenance.
std::string allocator_configuration();

}  // namespace dtsl
