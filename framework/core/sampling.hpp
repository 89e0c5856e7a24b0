// Area-uniform sampling of a triangle mesh, shared by the datasets (area sampler) and the metrics
// (100k samples on result and ground truth, docs/design.md §5).
#pragma once

#include <random>
#include <vector>

#include "framework/core/types.hpp"

namespace dtsl {

struct SurfaceSample {
  Vec3 point;
  Vec3 normal;  ///< the unit normal of the triangle it lies on
  int face;
};

/// `count` points distributed uniformly by area over the mesh (degenerate faces get none). With
/// `density`, the probability of a triangle is proportional to area x density(centroid) instead.
std::vector<SurfaceSample> sample_surface(const TriangleMesh& mesh, std::size_t count, std::mt19937_64& rng);

template <class Density>
std::vector<SurfaceSample> sample_surface_weighted(const TriangleMesh& mesh, std::size_t count,
                                                   std::mt19937_64& rng, const Density& density);

/// Unit normal of face f (zero for a degenerate face) and its area.
Vec3 face_normal(const TriangleMesh& mesh, int f);
double face_area(const TriangleMesh& mesh, int f);

// ---- implementation of the template ------------------------------------------------------------

std::vector<SurfaceSample> sample_faces(const TriangleMesh& mesh, std::size_t count, std::mt19937_64& rng,
                                        const std::vector<double>& face_weights);

template <class Density>
std::vector<SurfaceSample> sample_surface_weighted(const TriangleMesh& mesh, std::size_t count,
                                                   std::mt19937_64& rng, const Density& density) {
  std::vector<double> w(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& t = mesh.faces[f];
    const Vec3 c = (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0;
    w[f] = face_area(mesh, static_cast<int>(f)) * density(c);
  }
  return sample_faces(mesh, count, rng, w);
}

}  // namespace dtsl
