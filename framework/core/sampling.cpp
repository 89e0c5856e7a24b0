#include "framework/core/sampling.hpp"

#include <algorithm>
#include <cmath>

#include "framework/core/error.hpp"

namespace dtsl {

Vec3 face_normal(const TriangleMesh& mesh, int f) {
  const Face& t = mesh.faces[f];
  const Vec3 n = (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
  const double len = n.norm();
  return len > 0.0 ? Vec3(n / len) : Vec3::Zero();
}

double face_area(const TriangleMesh& mesh, int f) {
  const Face& t = mesh.faces[f];
  return 0.5 * (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]).norm();
}

std::vector<SurfaceSample> sample_faces(const TriangleMesh& mesh, std::size_t count, std::mt19937_64& rng,
                                        const std::vector<double>& face_weights) {
  std::vector<double> cumulative(face_weights.size());
  double total = 0.0;
  for (std::size_t f = 0; f < face_weights.size(); ++f) {
    const double w = face_weights[f];
    total += (std::isfinite(w) && w > 0.0) ? w : 0.0;
    cumulative[f] = total;
  }
  if (!(total > 0.0)) throw AlgorithmError("cannot sample a mesh with no triangle of positive area");
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<SurfaceSample> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double r = uniform(rng) * total;
    std::size_t f = static_cast<std::size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), r) - cumulative.begin());
    f = std::min(f, cumulative.size() - 1);
    // Uniform point in the triangle by the square-root parametrisation.
    const double s = std::sqrt(uniform(rng)), t = uniform(rng);
    const Face& tri = mesh.faces[f];
    const Vec3 p = (1.0 - s) * mesh.vertices[tri[0]] + s * (1.0 - t) * mesh.vertices[tri[1]] +
                   s * t * mesh.vertices[tri[2]];
    out.push_back({p, face_normal(mesh, static_cast<int>(f)), static_cast<int>(f)});
  }
  return out;
}

std::vector<SurfaceSample> sample_surface(const TriangleMesh& mesh, std::size_t count, std::mt19937_64& rng) {
  std::vector<double> w(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) w[f] = face_area(mesh, static_cast<int>(f));
  return sample_faces(mesh, count, rng, w);
}

}  // namespace dtsl
