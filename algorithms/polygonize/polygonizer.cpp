// The polygonizer registry, the plugin wrappers around the free functions, and the summary.
#include "algorithms/polygonize/polygonizer.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <unordered_map>

#include "algorithms/polygonize/marching_cubes.hpp"
#include "algorithms/polygonize/marching_triangulation.hpp"

namespace dtsl {

MeshQuality mesh_quality(const TriangleMesh& mesh) {
  // Same definitions as the metrics module's mesh_stats (docs/design.md §5): every face's smallest angle
  // (0 for a degenerate one), the nearest-rank 1st percentile, valence = number of distinct edges.
  MeshQuality q;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> angles;
  angles.reserve(mesh.faces.size());
  std::unordered_map<std::uint64_t, int> edge_faces;
  const auto angle = [](const Vec3& u, const Vec3& v) { return std::atan2(u.cross(v).norm(), u.dot(v)); };
  for (const Face& t : mesh.faces) {
    const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    angles.push_back(repeated ? 0.0
                              : std::min({angle(b - a, c - a), angle(c - b, a - b), angle(a - c, b - c)}) * 180.0 / M_PI);
    if (repeated) continue;
    for (int k = 0; k < 3; ++k) {
      std::uint32_t u = static_cast<std::uint32_t>(t[static_cast<std::size_t>(k)]);
      std::uint32_t v = static_cast<std::uint32_t>(t[static_cast<std::size_t>((k + 1) % 3)]);
      if (u > v) std::swap(u, v);
      ++edge_faces[(static_cast<std::uint64_t>(u) << 32) | v];
    }
  }
  if (angles.empty()) {
    q.min_angle_deg = q.min_angle_p01_deg = q.min_angle_mean_deg = q.valence6_fraction = nan;
    return q;
  }
  q.min_angle_mean_deg = std::accumulate(angles.begin(), angles.end(), 0.0) / static_cast<double>(angles.size());
  q.min_angle_deg = *std::min_element(angles.begin(), angles.end());
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.01 * static_cast<double>(angles.size())));
  const auto nth = angles.begin() + static_cast<long>(rank > 0 ? rank - 1 : 0);
  std::nth_element(angles.begin(), nth, angles.end());
  q.min_angle_p01_deg = *nth;

  std::vector<int> valence(mesh.vertices.size(), 0);
  std::vector<char> boundary(mesh.vertices.size(), 0), used(mesh.vertices.size(), 0);
  for (const auto& e : edge_faces) {
    const auto u = static_cast<std::size_t>(e.first >> 32), v = static_cast<std::size_t>(e.first & 0xFFFFFFFFu);
    ++valence[u];
    ++valence[v];
    used[u] = used[v] = 1;
    if (e.second == 1) {
      ++q.boundary_edges;
      boundary[u] = boundary[v] = 1;
    }
  }
  std::size_t interior = 0, six = 0;
  for (std::size_t v = 0; v < valence.size(); ++v)
    if (used[v] && !boundary[v]) {
      ++interior;
      six += valence[v] == 6 ? 1 : 0;
    }
  q.valence6_fraction = interior ? static_cast<double>(six) / static_cast<double>(interior) : nan;
  return q;
}

nlohmann::json to_json(const MeshQuality& q) {
  return {{"min_angle_deg", q.min_angle_deg},
          {"min_angle_p01_deg", q.min_angle_p01_deg},
          {"min_angle_mean_deg", q.min_angle_mean_deg},
          {"valence6_fraction", q.valence6_fraction},
          {"boundary_edges", q.boundary_edges}};
}

nlohmann::json to_json(const PolygonizeSummary& s) {
  return {{"method", s.method},
          {"vertices", s.vertices},
          {"faces", s.faces},
          {"components", s.components},
          {"seed_candidates", s.seed_candidates},
          {"seed_failures", s.seed_failures},
          {"seeds_outside_domain", s.seeds_outside_domain},
          {"dropped_components", s.dropped_components},
          {"open_boundaries", s.open_boundaries},
          {"seconds", s.seconds},
          {"triangles_per_second", s.seconds > 0.0 ? static_cast<double>(s.faces) / s.seconds : 0.0},
          {"quality", to_json(s.quality)},
          {"details", s.details}};
}

namespace {

class MarchingTriangulationPlugin final : public Polygonizer {
 public:
  Options& options() override { return options_; }
  PolygonizeResult polygonize(const ImplicitFunction& f, const std::vector<Vec3>& seeds_hint) override {
    return marching_triangulation(f, seeds_hint, options_);
  }

 private:
  MarchingTriangulationOptions options_;
};

class MarchingCubesPlugin final : public Polygonizer {
 public:
  Options& options() override { return options_; }
  PolygonizeResult polygonize(const ImplicitFunction& f, const std::vector<Vec3>& seeds_hint) override {
    return marching_cubes(f, seeds_hint, options_);
  }

 private:
  MarchingCubesOptions options_;
};

}  // namespace

Registry<Polygonizer>& polygonizers() {
  static Registry<Polygonizer> registry("polygonizer");
  return registry;
}

void register_polygonizers() {
  Registry<Polygonizer>& r = polygonizers();
  if (!r.contains("marching_triangulation"))
    r.add("marching_triangulation",
          "Hartmann's marching triangulation with the paper's seven-step seeding (semi-regular, paper §2.2)",
          [] { return std::make_unique<MarchingTriangulationPlugin>(); });
  if (!r.contains("marching_cubes"))
    r.add("marching_cubes", "marching tetrahedra on a Kuhn-split grid of spacing step, components carrying data kept",
          [] { return std::make_unique<MarchingCubesPlugin>(); });
}

}  // namespace dtsl
