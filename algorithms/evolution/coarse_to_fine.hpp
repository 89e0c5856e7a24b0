// Coarse-to-fine evolution (ours, after [55]'s adaptive refinement; docs/design.md §1 "the T-mesh's adaptive
// refinement ... not optional"). The evolution runs first on the data-adaptive T-mesh, which is
// coarse (points_per_cell keeps n_t near the paper's ~1000-2500) and therefore fast, and captures the
// topology and outline. A coarse T-mesh cannot bend into thin parts and narrow concavities (a part
// thinner than two cells stays wrapped in a blob away from its data: docs/design.md §8), so each
// round then splits, by one level, the leaves that hold data or that the zero set crosses near data,
// moves f onto the finer T-mesh unchanged (level_set_transfer.hpp), and evolves again from there. The
// later rounds start close to the data and need few steps.
#pragma once

#include <string>
#include <vector>

#include "algorithms/tspline/tspline.hpp"
#include "framework/config/options.hpp"

namespace dtsl {

struct CoarseToFineOptions final : Options {
  int levels = 1;
  int points_per_cell = 4;
  double data_reach = 2.0;
  int max_iterations = 60;
  double w_distance = 0.1;

  void visit(FieldVisitor& v) override {
    v.field("levels", levels,
            "refine-and-evolve rounds after the first evolution, one octree level each (capped at "
            "tmesh_max_depth); 0: evolve on the initial T-mesh only");
    v.field("points_per_cell", points_per_cell,
            "a leaf holding at least this many data points is split in a round");
    v.field("data_reach", data_reach,
            "a leaf the zero set crosses is split if a data point lies within data_reach x its side of the "
            "surface in it (lets the surface follow the data it is still approaching)");
    v.field("max_iterations", max_iterations, "iteration cap of each round's evolution");
    v.field("w_distance", w_distance,
            "distance-field weight w_D in the rounds (-1: the evolution's w_distance; 0.1, ours: docs/design.md "
            "§8); the first evolution keeps the topology-safe weight, a round starting near the data can follow "
            "it more closely");
  }
  void check() const override {
    check_range("levels", levels, 0, 10);
    check_range("points_per_cell", points_per_cell, 1, 1000000);
    check_range("data_reach", data_reach, 0.0, 100.0);
    check_range("max_iterations", max_iterations, 0, 100000);
    require(w_distance == -1.0 || w_distance >= 0.0, "w_distance", "must be -1 (the evolution's) or >= 0");
  }
};

/// The leaves of f's T-mesh below `level` that hold at least options.points_per_cell points or that
/// the zero set crosses within options.data_reach leaf sides of a point, split once (rebalanced), and
/// f moved onto the result. Returns f itself when nothing is to be split.
TSpline refine_toward_data(const TSpline& f, const std::vector<Vec3>& points, int level,
                           const CoarseToFineOptions& options);

}  // namespace dtsl
