// Grid polygonizer: f sampled on a grid of spacing delta and its zero set extracted cell by cell — the
// classical alternative to marching triangulation the paper names in §2.2 (Lorensen and Cline, ref
// [34]). Each cube is split into the six Kuhn (Freudenthal) tetrahedra around its main diagonal and
// each tetrahedron is polygonized on its own ("marching tetrahedra"): every cube uses the same split,
// so neighbouring cubes agree on their shared face diagonals and the surface has no cracks and no
// ambiguous faces, unlike the 15-case marching-cubes table. Vertices are shared by grid edge, so the
// mesh comes out indexed, closed and edge-manifold for a level set that stays inside the grid. A sample
// within 0.5 % of its neighbour differences of zero is nudged outside, so the surface never passes
// (almost) through a node, where clusters of near-coincident vertices would make tiny triangles cross.
#pragma once

#include <string>
#include <vector>

#include "algorithms/polygonize/newton_projection.hpp"
#include "algorithms/polygonize/polygonizer.hpp"
#include "framework/config/options.hpp"
#include "framework/core/implicit.hpp"

namespace dtsl {

struct MarchingCubesOptions final : Options {
  /// Grid spacing delta (frame units).
  double step = 0.03;
  /// Where the grid goes: "domain" (f's domain box) or "data" (the data's bounding box grown by
  /// `margin`; falls back to the domain without data). "data" is cheaper but cuts the surface open
  /// where the level set bulges out of that box.
  std::string region = "domain";
  /// Growth of the data box for region = "data" (frame units).
  double margin = 0.1;
  /// Vertex on a grid edge: "linear" interpolation of the two samples, or "root": a few regula-falsi
  /// steps along the edge to f = 0. Both keep the vertex on its edge, so the mesh stays free of
  /// self-intersections.
  std::string vertex_placement = "root";
  /// Also move every vertex onto f = 0 by Newton (off its grid edge: the most accurate, but a vertex
  /// of a sliver triangle may then cross a neighbour's triangle).
  bool newton_project = false;
  /// With data points: keep only the components some data foot point lies on (within
  /// cover_distance x step), as marching triangulation's seeding does; without data everything is kept.
  bool drop_dataless_components = true;
  /// Distance (x step) within which a foot point marks a component as carrying data.
  double cover_distance = 0.5;
  /// Cap on the grid size; above it the step is too fine for the region (AlgorithmError).
  int max_grid_nodes = 50'000'000;
  /// Newton projection (foot points, optional vertex projection): tolerance on |f|/|grad f|.
  double newton_tolerance = 1e-10;
  /// Newton projection: iteration cap.
  int newton_max_iterations = 50;

  void visit(FieldVisitor& v) override;
  void check() const override;
  NewtonOptions newton() const;
};

/// Throws AlgorithmError for a grid above max_grid_nodes or a level set with no sign change on it.
PolygonizeResult marching_cubes(const ImplicitFunction& f, const std::vector<Vec3>& data,
                                const MarchingCubesOptions& options);

}  // namespace dtsl
