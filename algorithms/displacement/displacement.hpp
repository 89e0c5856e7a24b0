// Phase 2: the displaced mesh M = M_0 + D (paper §3.2, Eq. 1-2; docs/design.md §3). The data's signed
// displacements d_k at their foot points q_k (projection.hpp) are filtered onto the vertices
// (displacement_filter.hpp, a plugin), their bias reduced by residual passes (residual_passes.hpp),
// vertices without data filled (hole_treatment.hpp, a plugin; their rims and spikes join them:
// hole_rim.hpp, spikes.hpp), and every vertex moves along the implicit normal: v <- v + d(v) n(v),
// n = grad f / |grad f| (paper: "the normals n are computed from the implicitly defined T-spline surface
// instead of the discretized mesh"). The flip check (flip_check.hpp) flags displaced triangles that
// flipped; the pipeline then refines the level set and redoes this stage (refine_on_flip.hpp).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "algorithms/displacement/displacement_filter.hpp"
#include "algorithms/displacement/projection.hpp"
#include "framework/config/options.hpp"
#include "framework/core/implicit.hpp"
#include "framework/core/types.hpp"

namespace dtsl {

struct DisplacementOptions final : Options {
  /// The displacement filter (displacement_filter.hpp): `adaptive` (ours) or `gaussian` (the paper's),
  /// which follows noisy data closer and ends farther from the truth (docs/experiments.md, "Noise").
  std::string filter = "adaptive";
  /// The paper's Gaussian width, x the base mesh's mean edge length (~ the marching step delta): the
  /// `gaussian` filter's width, the `adaptive` one's narrowest. Wider: less ripple, less detail
  /// (docs/experiments.md, "The displacement's filter").
  double sigma_factor = 0.5;
  /// Residual passes (residual_passes.hpp; 0: the paper's single filter). Each removes more of the
  /// filter's bias and lets more noise through (docs/experiments.md, "The displacement's filter").
  int residual_passes = 3;
  /// Fine residual passes with the paper's narrow mean after the `adaptive` filter's plane fit on
  /// noise-free data (0: off; docs/experiments.md, "Fine residual passes").
  int fine_residual_passes = 3;
  /// What fills the vertices without data (hole_treatment.hpp): `thin_plate`, `membrane` or `harmonic`.
  std::string hole_fill = "thin_plate";
  /// A hole's rim (hole_rim.hpp, ours; 0 off): a vertex beside a hole whose base filter's feet have their
  /// weighted centroid farther than this x the filter's width from it in the tangent plane (feet to one
  /// side: an extrapolation) joins the hole. A straight rim of even data puts the centroid sqrt(2/pi) ~
  /// 0.8 widths away (docs/experiments.md, "Where a hole's fill starts").
  double rim_offset = 0.8;
  /// The `adaptive` filter on noise-free data sparser than the mesh (displacement_filter.hpp, ours): the
  /// vertices with no data within the paper's support are `fit` (the wide plane fit carries the surface
  /// across them) or `margin` (holes, faired by the hole fill, except within the wide
  /// filter's reach of a hole in the data, where the fit carries the data's surface across its edge; a
  /// hole is deeper than that reach in the local spacing at its edge). docs/design.md §8, "Gaps between
  /// sparse data" and "Where a hole's margin starts".
  std::string gaps = "margin";

  void visit(FieldVisitor& v) override;
  void check() const override;
};

struct DisplacementResult {
  TriangleMesh mesh;                        ///< the displaced mesh, vertex normals from grad f at the base vertex
  std::vector<double> vertex_displacement;  ///< d(v) per vertex; for a faired hole vertex the normal part of its move
  std::vector<int> hole_vertices;           ///< vertices without data near them: filled (hole_treatment.hpp)
  std::vector<int> at_risk_vertices;        ///< |d(v)| towards a centre of curvature >= half its radius
  std::vector<int> flipped_faces;           ///< faces whose normal reversed (among those tested)
  std::vector<int> flipped_vertices;        ///< vertices of flipped faces: where to refine the level set
  bool needs_refinement = false;            ///< a flip happened: refine f (final refinement) and redo
  ProjectionResult projection;
  DataScale scale;                          ///< what the filter measured of the data (reusable: `scale` below)
  nlohmann::json summary;                   ///< counts, flips, holes, e_avr/e_max before/after, seconds
};

/// Paper §3.1-3.2 on `base` (the initial mesh M_0 of f = 0). `scale`: the data's noise and spacing
/// measured by an earlier call on the same points (nullptr: measured here, as the filter needs).
/// Throws ConfigError for invalid options, AlgorithmError for no data points, a non-finite point, or
/// an empty / invalid mesh.
DisplacementResult displace_mesh(const ImplicitFunction& f, const TriangleMesh& base, const std::vector<Vec3>& points,
                                 const DisplacementOptions& options = {}, const DataScale* scale = nullptr);

/// Constructs the displacement filter and hole treatment registries, so that `dtsl list` shows them.
/// Idempotent.
void register_displacers();

}  // namespace dtsl
