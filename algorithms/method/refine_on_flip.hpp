// Paper §3.2's fallback for flipped triangles: where displacing MI flips triangles, refine the level set
// one octree level near the flips (final refinement with the flips as focus), triangulate it again and
// displace again, at most `rounds` times. A round is kept only when it flips fewer triangles and the
// data are no farther from its mesh (e_avr); one that cannot refine, cannot be triangulated at MI's
// step, leaves the data's bounds or changes the topology Phase 1 found (a fit near a thin part can open
// a spurious handle) ends the loop.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "algorithms/displacement/displacement.hpp"
#include "algorithms/evolution/final_refinement.hpp"
#include "algorithms/polygonize/polygonizer.hpp"
#include "algorithms/tspline/tspline.hpp"

namespace dtsl {

/// A level set and its triangulation MI, the base the displacement starts from.
struct MeshedLevelSet {
  TSpline f;
  PolygonizeResult mi;
  double step = 0.0;     ///< the marching step MI was made with
  int halvings = 0;      ///< the step halvings it took
  std::string fallback;  ///< why the fallback polygonizer made it ("": it did not)
  std::vector<std::string> halving_reasons;  ///< the polygonizer's error at each step that failed
};

/// How a round refines and triangulates: the pipeline's refinement, solver and polygonizers.
struct FlipRefinement {
  int rounds = 2;
  FinalRefinementOptions refine;  ///< its target_level is set per round, one below the finest leaves
  std::string solver = "eigen_cg";  ///< the level-set solver plugin of the refits, created by the loop
  /// Triangulates MeshedLevelSet::f into its mi at exactly its step, with the polygonizer that made the
  /// current MI (its fallback named); throws AlgorithmError when f does not mesh there. No step halving:
  /// a refined zero set with detail below MI's step is one the displacement should carry instead
  /// (paper §3), and halving would multiply the mesh and its cost for a round that is rarely kept.
  std::function<void(MeshedLevelSet&)> triangulate;
  /// Throws AlgorithmError for a triangulation outside the data's bounds.
  std::function<void(TriangleMesh&)> check;
};

/// e_avr of the data to a displaced mesh (its summary's errors_after, paper §4).
double mean_data_distance(const DisplacementResult& dr);

/// Why a refinement round's displacement `round` is not kept over `kept` ("" : it is kept): it must
/// flip fewer faces and leave the data no farther from the mesh (e_avr).
std::string round_refusal(const DisplacementResult& kept, const DisplacementResult& round);

/// Displaces `current.mi` onto `points` and refines on flips as above; `current` ends as the base of
/// the displacement returned. The summary gains `flips_per_round` (flipped faces per round, or why a
/// round was refused), `e_avr_per_round` (the data's mean distance to each displaced mesh) and
/// `refinement_round_seconds`. The topology is judged on the refined MI before it is displaced.
/// ConfigError for an unknown solver.
DisplacementResult displace_refining_on_flips(MeshedLevelSet& current, const std::vector<Vec3>& points,
                                              const std::vector<Vec3>& level_set_points,
                                              const DisplacementOptions& options, const FlipRefinement& how);

}  // namespace dtsl
