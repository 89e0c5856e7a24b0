// Shared checks of the fuzz targets: what a reader returns must be usable as it stands (finite
// coordinates, indices in range, normals one per vertex or none), and a rejected input must be
// rejected with a dtsl::Error, never another exception (which would reach the user without the file's
// name), a crash or a hang. A violation calls __builtin_trap() so libFuzzer records the input.
#pragma once

#include <cstdio>
#include <cstdlib>

#include "framework/core/types.hpp"

namespace dtsl::fuzz {

[[noreturn]] inline void violated(const char* what) {
  std::fprintf(stderr, "fuzz property violated: %s\n", what);
  __builtin_trap();
}

inline void check_mesh(const TriangleMesh& m) {
  for (const Vec3& v : m.vertices)
    if (!v.allFinite()) violated("a vertex with a NaN or infinite coordinate was accepted");
  for (const Vec3& n : m.normals)
    if (!n.allFinite()) violated("a normal with a NaN or infinite coordinate was accepted");
  if (!m.normals.empty() && m.normals.size() != m.vertices.size())
    violated("normals are neither absent nor one per vertex");
  const long long nv = static_cast<long long>(m.vertices.size());
  for (const Face& f : m.faces)
    for (int c = 0; c < 3; ++c)
      if (f[c] < 0 || f[c] >= nv) violated("a face index out of range was accepted");
}

}  // namespace dtsl::fuzz
