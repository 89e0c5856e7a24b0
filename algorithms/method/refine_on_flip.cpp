// Paper §3.2: refine the level set near flipped triangles and displace again.
#include "algorithms/method/refine_on_flip.hpp"

#include <algorithm>
#include <memory>

#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"
#include "framework/metrics/metrics.hpp"

namespace dtsl {

namespace {

// The level set refined one level near the flips of `dr` on current.mi; nullopt when nothing is left
// to refine there.
std::optional<TSpline> refined_near_flips(const MeshedLevelSet& current, const DisplacementResult& dr,
                                          const std::vector<Vec3>& level_set_points, const FlipRefinement& how,
                                          LevelSetSolver& solver) {
  std::vector<Vec3> focus;
  for (int v : dr.flipped_vertices) focus.push_back(current.mi.mesh.vertices[v]);
  FinalRefinementOptions refine = how.refine;
  refine.target_level = std::min(current.f.tmesh().finest_leaf_level() + 1, current.f.tmesh().max_depth());
  RefinedLevelSet refined =
      refine_level_set(current.f, level_set_points, refine, solver, focus, WhenNothingToSplit::skip_fit);
  if (refined.report.rounds == 0) return std::nullopt;
  return std::move(refined.level_set);
}

bool same_topology(const TriangleMesh& a, const TriangleMesh& b) {
  const MeshStats before = mesh_stats(a), after = mesh_stats(b);
  return after.euler_characteristic == before.euler_characteristic && after.components == before.components;
}

}  // namespace

double mean_data_distance(const DisplacementResult& dr) { return dr.summary.at("errors_after").at("e_avr").get<double>(); }

std::string round_refusal(const DisplacementResult& kept, const DisplacementResult& round) {
  const std::size_t flips = round.flipped_faces.size();
  if (flips >= kept.flipped_faces.size()) return std::to_string(flips) + " flips, not fewer: refused";
  // Fewer flips bought by a mesh farther from the data is no better.
  if (mean_data_distance(round) > mean_data_distance(kept)) return std::to_string(flips) + " flips but e_avr rose: refused";
  return "";
}

DisplacementResult displace_refining_on_flips(MeshedLevelSet& current, const std::vector<Vec3>& points,
                                              const std::vector<Vec3>& level_set_points,
                                              const DisplacementOptions& options, const FlipRefinement& how) {
  const std::unique_ptr<LevelSetSolver> solver = level_set_solvers().create(how.solver, "solver");
  DisplacementResult dr = displace_mesh(current.f, current.mi.mesh, points, options);
  const DataScale scale = dr.scale;  // the data do not change between rounds: measured once
  nlohmann::json flips = nlohmann::json::array({dr.flipped_faces.size()}), seconds = nlohmann::json::array();
  nlohmann::json e_avr = nlohmann::json::array({mean_data_distance(dr)});
  for (int round = 0; round < how.rounds && dr.needs_refinement; ++round) {
    Stopwatch part;
    std::optional<TSpline> refined = refined_near_flips(current, dr, level_set_points, how, *solver);
    nlohmann::json round_seconds = {{"refine", part.seconds()}};
    if (!refined) break;  // nothing left to refine near the flips
    MeshedLevelSet next{std::move(*refined), PolygonizeResult{}, current.step, current.halvings, current.fallback,
                        current.halving_reasons};
    try {
      part.restart();
      how.triangulate(next);
      round_seconds["polygonize"] = part.seconds();
    } catch (const AlgorithmError&) {
      seconds.push_back(round_seconds);
      flips.push_back("does not mesh at MI's step: refused");
      break;
    }
    try {
      how.check(next.mi.mesh);
    } catch (const AlgorithmError&) {
      flips.push_back("refined zero set out of bounds: refused");
      break;
    }
    // The refinement may not change the topology Phase 1 found: judged on the new MI, before the
    // displacement is paid for.
    if (!same_topology(current.mi.mesh, next.mi.mesh)) {
      seconds.push_back(round_seconds);
      flips.push_back("topology changed: refused");
      break;
    }
    part.restart();
    DisplacementResult again = displace_mesh(next.f, next.mi.mesh, points, options, &scale);
    for (const char* key : {"noise_estimated", "noise_estimate"})  // what the figure came from
      if (dr.summary.contains(key)) again.summary[key] = dr.summary[key];
    round_seconds["displace"] = part.seconds();
    seconds.push_back(round_seconds);  // where D-Map's time goes (docs/performance.md)
    e_avr.push_back(mean_data_distance(again));
    const std::string refused = round_refusal(dr, again);
    flips.push_back(refused.empty() ? nlohmann::json(again.flipped_faces.size()) : nlohmann::json(refused));
    if (!refused.empty()) break;
    current = std::move(next);
    dr = std::move(again);
  }
  dr.summary["flips_per_round"] = flips;
  dr.summary["refinement_round_seconds"] = seconds;
  dr.summary["e_avr_per_round"] = e_avr;
  return dr;
}

}  // namespace dtsl
