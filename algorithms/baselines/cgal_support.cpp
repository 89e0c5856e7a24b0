#include "algorithms/baselines/cgal_support.hpp"

#include <limits>

#include "framework/core/error.hpp"

namespace dtsl::baselines {

TriangleMesh interpolating_mesh(const std::vector<Vec3>& vertices, const std::vector<std::array<std::size_t, 3>>& facets,
                                nlohmann::json& summary) {
  if (vertices.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw AlgorithmError("too many vertices for a mesh: " + std::to_string(vertices.size()));
  PolygonSoup soup;
  soup.vertices = vertices;
  soup.polygons.reserve(facets.size());
  for (const auto& f : facets)  // an index past the vertices becomes -1: soup_to_mesh drops it
    soup.polygons.push_back({f[0] < vertices.size() ? static_cast<int>(f[0]) : -1,
                             f[1] < vertices.size() ? static_cast<int>(f[1]) : -1,
                             f[2] < vertices.size() ? static_cast<int>(f[2]) : -1});
  CleanupCounts counts;
  TriangleMesh mesh = soup_to_mesh(soup, 0.0, false, &counts);
  Vec3 centre = Vec3::Zero();
  for (const Vec3& v : mesh.vertices) centre += v;
  if (!mesh.vertices.empty()) centre /= static_cast<double>(mesh.vertices.size());
  summary["flipped_outward"] = orient_outward(mesh, centre);
  summary["cleanup"] = counts.to_json();
  return mesh;
}

}  // namespace dtsl::baselines
