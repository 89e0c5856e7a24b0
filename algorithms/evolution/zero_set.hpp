// Where the evolution looks at the level set each step (docs/design.md §1): points x_j on the current zero
// set, where the velocity rows are written, and points y_m of a band around it, where the
// distance-field rows keep |grad f| near 1.
//
// x_j: the centres of the s^3 sub-cells of every leaf cell, each projected onto f = 0 by Newton and
// kept if its foot point stays in its own sub-cell — about s^2 points per leaf the surface crosses,
// so the rows follow the T-mesh's resolution: dense where the data are dense, sparse where the T-mesh
// is coarse. s = 2 by default: with one point per leaf (s = 1) the velocity is prescribed at too few
// points for the ~s^3-per-leaf freedom of a cubic spline in a cell, and f' develops bumps between them
// that grow into spurious components (docs/design.md §8). Nothing about the number of components or the genus is assumed:
// every leaf is looked at, every step.
// y_m: the centres of the b^3 sub-cells (b = 1: the leaf centres) where |f| / |grad f| < band_width x
// (the side of their leaf), plus the x_j. docs/design.md §1 writes the band as |f| < 2 h_min; on an adaptive T-mesh a band of the finest cell
// size would hold no cell centre at all where the T-mesh is coarse, so the band is measured in the
// local cell size (ours).
#pragma once

#include <vector>

#include "algorithms/tspline/tspline.hpp"

namespace dtsl {

struct ZeroSetSampling {
  int subdivision = 2;       ///< s: zero-set candidates are the centres of s^3 sub-cells of every leaf
  int band_subdivision = 2;  ///< band candidates: the centres of b^3 sub-cells of every leaf
  double band_width = 2.0;   ///< band: |f| / |grad f| < band_width x the leaf's side
  int newton_iterations = 8; ///< Newton steps per candidate (a step is capped at the sub-cell side)
  bool hessians = true;      ///< evaluate the Hessian at the x_j (for the curvature)
};

struct SurfacePoint {
  Vec3 position;
  Vec3 gradient;
  Mat3 hessian;      ///< zero unless ZeroSetSampling::hessians
  double cell_size;  ///< side of the leaf holding the point
  int leaf;          ///< leaf number of the T-mesh sampled
};

struct ZeroSetSamples {
  std::vector<SurfacePoint> surface;   ///< the x_j
  std::vector<Vec3> band;              ///< the y_m (the x_j included)
  std::vector<Vec3> band_gradient;     ///< grad f(y_m)
  std::vector<double> band_cell_size;  ///< leaf side at y_m
  /// y_m's site: leaf x b^3 + sub-cell for the sub-cell centres (the same points at every call on one
  /// T-mesh, b = band_subdivision: GradientCache), -1 for the zero-set points among the y_m.
  std::vector<int> band_site;
};

/// Samples the zero set and band of f on the T-mesh `tmesh` (usually f's own; the final refinement
/// samples the old f on the refined T-mesh). OpenMP-parallel, deterministic for a given thread count.
ZeroSetSamples sample_zero_set(const ImplicitFunction& f, const Octree& tmesh, const ZeroSetSampling& options);

}  // namespace dtsl
