// Moving a level set onto a refined T-mesh (the final refinement and the coarse-to-fine evolution,
// docs/design.md §1). Control points whose knot vectors did not change keep their coefficient (f is
// unchanged where only they are active); the new or changed ones get either
//  - `quasi_interpolation` (the options' default): the old f at their Greville point, O(h^2) in the
//    old cell size h; or
//  - `least_squares` (ours): the discrete least-squares fit to the old f over 2^3 samples of every leaf
//    where a changed function is active (so small leaves, near the surface, weigh more per volume),
//    starting from the quasi-interpolant.
// A refined T-spline space need not contain the coarse one, so no transfer is exact; the
// quasi-interpolant moves the zero set by a sizeable part of the data's distance to it (a 24k-point
// noisy diplodocus's mean data distance 4.73e-3 -> 7.81e-3 by the transfer alone, 4.74e-3 with least
// squares), which the fit after it then has to undo. It does, about as well from either start, so the
// final meshes barely differ; in the coarse-to-fine round the least-squares start made fandisk and the
// holed bunny worse (chamfer fandisk 7.73e-3 -> 8.74e-3, holed bunny 1.86e-3 -> 2.30e-3 after the round).
// Either way f changes only where knots changed.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "algorithms/tspline/tspline.hpp"

namespace dtsl {

enum class Transfer { quasi_interpolation, least_squares };
Transfer transfer_from_string(const std::string& name);  // ConfigError naming the value
const char* to_string(Transfer t);

/// The strongest 2:1 balance `tree` satisfies: refining with it keeps the T-mesh's kind.
Balance balance_of(const Octree& tree);

/// What a transfer did (the final refinement's record).
struct TransferReport {
  std::string method;
  int changed = 0;           ///< control points whose knots changed (refitted)
  int samples = 0;           ///< least squares: sample points in the fit
  int iterations = 0;        ///< least squares: CG iterations
  double cg_error = 0.0;     ///< least squares: CG's relative residual of the normal equations
  bool converged = true;     ///< least squares: CG met its tolerance (else its last iterate, still an improvement)
  double seconds = 0.0;
};
nlohmann::json to_json(const TransferReport& r);

/// `old` on the T-mesh `refined` (which must refine old's T-mesh over the same domain).
TSpline transfer_level_set(const TSpline& old, Octree refined, Transfer method, TransferReport* report = nullptr);

}  // namespace dtsl
