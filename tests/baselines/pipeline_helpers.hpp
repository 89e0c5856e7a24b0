// What the baseline tests share: a sampled sphere, pipelines created and configured by name as an
// experiment does, and the signed volume that tells an outward mesh.
#pragma once

#include <memory>
#include <random>
#include <string>

#include "experiments/plugins.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/pipeline/reconstructor.hpp"

namespace dtsl::test {

/// n points uniform on the sphere of `radius` about the origin, with exact outward normals if `normals`.
inline PointCloud sampled_sphere(std::size_t n, double radius, bool normals, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  PointCloud c;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 u = Vec3(g(rng), g(rng), g(rng)).normalized();
    c.points.push_back(radius * u);
    if (normals) c.normals.push_back(u);
  }
  return c;
}

inline std::unique_ptr<Reconstructor> create(const std::string& name) {
  register_all_plugins();
  return reconstructors().create(name, "test");
}

/// Sets one option as `--set key=value` does (checked at once).
inline void set(Reconstructor& r, const std::string& key, const std::string& value) {
  apply_assignment(r.options(), key, value, "test");
}

inline double signed_volume(const TriangleMesh& m) {
  double v = 0.0;
  for (const Face& f : m.faces) v += m.vertices[f[0]].dot(m.vertices[f[1]].cross(m.vertices[f[2]])) / 6.0;
  return v;
}

}  // namespace dtsl::test
