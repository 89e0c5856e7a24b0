#include "framework/core/types.hpp"

#include "framework/core/error.hpp"

#include <cmath>

namespace dtsl {

BoundingBox bounding_box(const std::vector<Vec3>& points) {
  BoundingBox box;
  for (const Vec3& p : points) box.extend(p);
  return box;
}

Similarity unit_cube_normalisation(const std::vector<Vec3>& points, const std::string& what) {
  if (points.empty()) throw AlgorithmError(what + ": no points to normalise");
  const BoundingBox box = bounding_box(points);
  const double longest = box.extent().maxCoeff();
  if (!(longest > 0.0) || !std::isfinite(longest))
    throw AlgorithmError(what + ": all points coincide (bounding box has zero size)");
  Similarity s;
  s.center = box.center();
  s.scale = 2.0 / longest;
  return s;
}

void transform(PointCloud& cloud, const Similarity& s) {
  for (Vec3& p : cloud.points) p = s.apply(p);
}

void transform(TriangleMesh& mesh, const Similarity& s) {
  for (Vec3& v : mesh.vertices) v = s.apply(v);
}

namespace {
void check_vectors(const std::vector<Vec3>& v, const std::string& what, const char* kind) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!v[i].allFinite())
      throw AlgorithmError(what + ": " + kind + " " + std::to_string(i) +
                           " has a NaN or infinite coordinate");
}
}  // namespace

void check_finite(const PointCloud& cloud, const std::string& what) {
  check_vectors(cloud.points, what, "point");
  check_vectors(cloud.normals, what, "normal");
}

void check_finite(const TriangleMesh& mesh, const std::string& what) {
  check_vectors(mesh.vertices, what, "vertex");
  check_vectors(mesh.normals, what, "normal");
}

}  // namespace dtsl
