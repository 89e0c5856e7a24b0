// Hartmann's marching triangulation of an implicit surface (Hartmann 1998, The Visual Computer
// 14:95-108; the paper's ref [21] and §2.2): from a seed on f = 0, a hexagon of triangles; then front
// polygons grow over the surface, always at the front point of smallest front angle, with new points
// made in the tangent plane at distance delta and projected onto f = 0 by Newton; fronts split and
// merge where they meet. Near-equilateral triangles of edge ~delta, most vertices of valence 6.
#pragma once

#include <string>
#include <vector>

#include "algorithms/polygonize/newton_projection.hpp"
#include "algorithms/polygonize/polygonizer.hpp"
#include "algorithms/polygonize/seeding.hpp"
#include "framework/config/options.hpp"
#include "framework/core/implicit.hpp"

namespace dtsl {

struct MarchingTriangulationOptions final : Options {
  /// Marching step delta (frame units): the target edge length. The paper takes 0.2 l_T, l_T the
  /// diameter of the finest T-mesh cells; it must stay well below the smallest curvature radius.
  double step = 0.03;
  /// Hartmann's distance check: a front point closer than this x step to a point of another part of
  /// its own front (or of another front) is joined to it, splitting (or merging) the fronts.
  double join_distance = 1.0;
  /// Seeding step 5: a foot point closer than this x step to a finished component's mesh is covered.
  double cover_distance = 0.25;
  /// Grid spacing (frame units) for finding seeds by sign changes when no data points are given.
  double seed_grid_step = 0.05;
  /// Cap on the number of components; more means a fragmented level set (AlgorithmError).
  int max_components = 10000;
  /// Cap on the triangles of one component; reaching it means a front that cannot close (AlgorithmError).
  int max_triangles = 20'000'000;
  /// Newton projection onto f = 0: stop when the step |f|/|grad f| is below this (frame units).
  double newton_tolerance = 1e-10;
  /// Newton projection: iteration cap.
  int newton_max_iterations = 50;

  void visit(FieldVisitor& v) override;
  void check() const override;
  NewtonOptions newton() const;
};

/// Counters of one or more marches.
struct MarchStatistics {
  std::size_t splits = 0;          ///< a front joined to a non-neighbour of itself: two fronts
  std::size_t merges = 0;          ///< two fronts joined into one (e.g. around a torus' tube)
  std::size_t slits_closed = 0;    ///< a front point between two copies of one vertex, closed up
  std::size_t open_boundaries = 0; ///< fronts left open where the surface leaves f's domain
  std::size_t newton_iterations = 0;
  std::size_t half_steps = 0;      ///< new points at a halved step (1-3 times) where the step failed (all marches)
};

/// One component from one seed (on or near f = 0). `skipped` when the seed cannot start a march (the
/// first hexagon does not fit: a component smaller than the step). Throws AlgorithmError for a front
/// that cannot close or a step too large for the curvature (where more than 1 % of its points needed a
/// halved step, or the component then covers itself twice: overlapping_sheets.hpp).
ComponentMesh march_component(const ImplicitFunction& f, const Vec3& seed, const MarchingTriangulationOptions& options,
                              MarchStatistics& statistics);

/// The paper's seven-step seeding around march_component: every component carrying data points,
/// each once. With no data points, seeds come from sign changes of f on a grid over the domain.
PolygonizeResult marching_triangulation(const ImplicitFunction& f, const std::vector<Vec3>& data,
                                        const MarchingTriangulationOptions& options);

}  // namespace dtsl
