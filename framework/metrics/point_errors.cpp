// The paper's Eq. 9: mean and maximum exact distance from the input points to the mesh.
#include <string>

#include "framework/core/error.hpp"
#include "framework/metrics/metrics.hpp"

namespace dtsl {

namespace {
MeshDistance distance_to(const TriangleMesh& mesh) {
  try {
    return MeshDistance(mesh);
  } catch (const AlgorithmError& e) {
    throw AlgorithmError(std::string("point errors: ") + e.what());
  }
}
}  // namespace

PointErrors point_errors(const std::vector<Vec3>& points, const TriangleMesh& mesh) {
  if (points.empty()) throw AlgorithmError("point errors: no points");
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite()) throw AlgorithmError("point errors: point " + std::to_string(i) + " is not finite");
  const MeshDistance distance = distance_to(mesh);
  PointErrors e;
  double sum = 0.0;  // in point order, so the result never depends on the query order or threads
  for (const MeshDistance::Hit& hit : distance.closest_all(points)) {
    sum += hit.distance;
    if (hit.distance > e.e_max) e.e_max = hit.distance;
  }
  e.e_avr = sum / static_cast<double>(points.size());
  return e;
}

}  // namespace dtsl
