// The polygonizer registry, the plugin wrappers around the free functions, and the summary.
#include "algorithms/polygonize/polygonizer.hpp"

#include "algorithms/polygonize/marching_cubes.hpp"
#include "algorithms/polygonize/marching_triangulation.hpp"
#include "framework/metrics/metrics.hpp"

namespace dtsl {

MeshQuality mesh_quality(const TriangleMesh& mesh) {
  const MeshStats s = mesh_stats(mesh);  // one definition of these numbers (docs/design.md §5)
  MeshQuality q;
  q.min_angle_deg = s.min_angle_deg;
  q.min_angle_p01_deg = s.min_angle_p01_deg;
  q.min_angle_mean_deg = s.min_angle_mean_deg;
  q.valence6_fraction = s.valence6_fraction;
  q.boundary_edges = s.boundary_edges;
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
  PolygonizeResult polygonize(const ImplicitFunction& f, const std::vector<Vec3>& seeds_hint, double step) override {
    MarchingTriangulationOptions o = options_;
    o.step = step;
    return marching_triangulation(f, seeds_hint, o);
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
  PolygonizeResult polygonize(const ImplicitFunction& f, const std::vector<Vec3>& seeds_hint, double step) override {
    MarchingCubesOptions o = options_;
    o.step = step;
    return marching_cubes(f, seeds_hint, o);
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
