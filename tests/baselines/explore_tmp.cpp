#include <catch2/catch.hpp>
#include <random>
#include <cstdio>
#include "experiments/plugins.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/metrics/metrics.hpp"
#include "framework/pipeline/reconstructor.hpp"
#include "framework/core/timer.hpp"
using namespace dtsl;
static PointCloud sph(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed); std::normal_distribution<double> g; PointCloud c;
  for (std::size_t i = 0; i < n; ++i) { Vec3 u = Vec3(g(rng), g(rng), g(rng)).normalized(); c.points.push_back(0.95*u); c.normals.push_back(u); }
  return c; }
TEST_CASE("explore", "[.explore]") {
  register_all_plugins();
  const char* name = getenv("M"); const char* sets = getenv("SETS"); std::size_t n = atoi(getenv("N"));
  for (int rep = 0; rep < (getenv("REPS") ? atoi(getenv("REPS")) : 2); ++rep) {
  auto r = reconstructors().create(name, "x");
  if (sets) { std::string s = sets; size_t p = 0; while (p < s.size()) { size_t q = s.find(',', p); if (q == std::string::npos) q = s.size(); std::string kv = s.substr(p, q-p); size_t e = kv.find('='); apply_assignment(r->options(), kv.substr(0,e), kv.substr(e+1), "x"); p = q+1; } }
  Stopwatch w; auto res = r->reconstruct(sph(n, 7), RunContext{}); double t = w.seconds();
  auto st = mesh_stats(res.mesh); double mean=0; for (auto& v: res.mesh.vertices) mean += std::abs(v.norm()-0.95); mean/=res.mesh.vertices.size();
  printf("%s n=%zu V=%zu F=%zu boundary=%zu nonman=%zu comps=%zu mean=%.2e minang_mean=%.1f t=%.2fs\n", name, n, res.mesh.vertices.size(), res.mesh.faces.size(), st.boundary_edges, st.nonmanifold_edges, st.components, mean, st.min_angle_mean_deg, t);
  }
}
#include <yaml-cpp/yaml.h>
#include "framework/datasets/dataset.hpp"
TEST_CASE("explore_real", "[.explore_real]") {
  register_all_plugins();
  YAML::Node cfg = YAML::LoadFile(std::string(DTSL_SOURCE_DIR) + "/configs/baselines.yaml");
  const char* only = getenv("M"); const char* ds = getenv("DS"); const char* sets = getenv("SETS");
  for (std::size_t i = 0; i < cfg["datasets"].size(); ++i) {
    DatasetSpec spec = parse_dataset(cfg["datasets"][i], "d");
    if (ds && spec.name != ds) continue;
    Dataset d = build_dataset(spec, 1);
    for (const char* name : {"pcl_poisson", "pcl_mc_hoppe", "pcl_mc_rbf", "pcl_gp3", "pcl_grid"}) {
      if (only && std::string(only) != name) continue;
      auto r = reconstructors().create(name, "x");
      if (sets) { std::string s = sets; size_t p = 0; while (p < s.size()) { size_t q = s.find(',', p); if (q == std::string::npos) q = s.size(); std::string kv = s.substr(p, q-p); size_t e = kv.find('='); apply_assignment(r->options(), kv.substr(0,e), kv.substr(e+1), "x"); p = q+1; } }
      Stopwatch w;
      try {
        auto res = r->reconstruct(d.points, RunContext{});
        double t = w.seconds();
        auto st = mesh_stats(res.mesh); auto pe = point_errors(d.points.points, res.mesh);
        auto sm = compare_surfaces(res.mesh, *d.ground_truth, 30000, 0.005, 1);
        { printf("%s %s n=%zu F=%zu wt=%d bnd=%zu comps=%zu e_avr=%.2f e_max=%.1f chamfer=%.2f F=%.3f t=%.1fs peak=%.0fMiB\n", d.name.c_str(), name, d.points.size(), res.mesh.faces.size(), (int)st.watertight, st.boundary_edges, st.components, pe.e_avr*1e3, pe.e_max*1e3, sm.chamfer*1e3, sm.fscore, t, peak_memory_mib());
        if (getenv("SUMMARY")) printf("%s\n", res.stages.back().summary.dump().c_str()); }
      } catch (const std::exception& e) { printf("%s %s n=%zu ERROR %s\n", d.name.c_str(), name, d.points.size(), e.what()); }
      fflush(stdout);
    }
  }
}
