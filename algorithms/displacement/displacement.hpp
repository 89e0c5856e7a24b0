// Phase 2: the displaced mesh M = M_0 + D (paper §3.2, Eq. 1-2; docs/design.md §3). The data's signed
// displacements d_k at their foot points q_k (projection.hpp) are Gaussian-filtered onto the vertices,
// holes get a harmonic fill, and every vertex moves along the implicit normal: v <- v + d(v) n(v),
// n = grad f / |grad f| (paper: "the normals n are computed from the implicitly defined T-spline surface
// instead of the discretized mesh"). The curvature check flags displaced triangles that flipped where
// |d(v)| approaches the smaller principal curvature radius; the pipeline then refines the level set
// (final refinement, evolution module) and redoes this stage.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "algorithms/displacement/noise_estimate.hpp"
#include "algorithms/displacement/projection.hpp"
#include "framework/config/options.hpp"
#include "framework/core/implicit.hpp"
#include "framework/core/types.hpp"
#include "framework/registry/registry.hpp"

namespace dtsl {

struct DisplacementOptions final : Options {
  /// Gaussian filter width (frame units); 0 = sigma_factor x the base mesh's mean edge length (~ the
  /// marching step delta, docs/design.md §3). Wider smooths noise more and small features more.
  double sigma = 0.0;
  /// sigma = sigma_factor x mean edge length when sigma is 0. 0.5 (ours; docs/design.md suggests ~1): with
  /// the residual passes, measured on fandisk cut by a plane, e_avr of MD 2.7e-3 at 1.0, 0.88e-3 at 0.5.
  double sigma_factor = 0.5;
  /// Foot points farther than this x sigma from a vertex are ignored (the Gaussian is ~1% there at 3).
  double support = 3.0;
  /// A vertex with fewer foot points than this within the support is a hole vertex (harmonic fill).
  int min_points = 1;
  /// A vertex whose Gaussian weights sum to less than this (all its foot points beyond ~2.4 sigma at
  /// 0.05) is a hole vertex too: normalising tiny weights extrapolates one far point's d (ours).
  double min_weight = 0.05;
  /// A vertex whose d differs from the mean d of its neighbours by more than this x the mean edge
  /// length is a spike (a foot point from another sheet, an extrapolated residual) and is refilled
  /// harmonically from its neighbours (ours; 0 disables). Real corners stay below ~1.
  double spike_factor = 3.0;
  /// A hole's rim (ours; 0 off): a vertex next to a hole vertex whose base filter's feet lie to one
  /// side, their Gaussian-weighted centroid more than this x the filter's width from it in the tangent
  /// plane, is a hole vertex too, ring after ring up to rim_rings. Its d is an extrapolation of the
  /// data across the rim (a one-sided fit); the hole's fill then starts nearer where the data stop.
  /// Enough feet all round a vertex put their centroid near it, so sparse data are not taken for a hole
  /// (a vertex with one to three feet can have its centroid anywhere, but only one beside a hole is
  /// tested). A vertex on a straight rim of even data has its centroid about sqrt(2/pi) ~ 0.8 x the
  /// width away, one inside the data less: 0.8 takes the vertices beyond the data's edge (one on the
  /// edge is borderline). configs/ablation_hole_rim.yaml. Default 0.8: with the fine residual passes
  /// and rim_min_hole_vertices 20 it lowers chamfer and costs little e_max (against rim 0: bunny 1.85 ->
  /// 1.59e-3, e_max 11.4 -> 8.8; fandisk 7.44 -> 6.26, e_max 9.6 -> 10.0, at bilateral_patience 1). It
  /// applies to noisy data too (the fine passes do not): diplodocus 0.96 -> 0.87, e_max 7.2 -> 7.9;
  /// armadillo 1.34, e_max 15.8 -> 10.8 (configs/method.yaml, configs/paper_table1.yaml).
  double rim_offset = 0.8;
  /// rim_offset tests only vertices whose base filter has at least this many feet: with fewer the
  /// centroid can lie anywhere (sparse data, not a rim).
  int rim_min_feet = 1;
  /// rim_offset grows only holes (connected vertices without data) of at least this many vertices: on
  /// sparse data the weight test leaves gaps of a vertex or two, which have no rim to extend.
  /// configs/ablation_rim_min_hole.yaml: at 20 the 10k noisy armadillo sample 3.85 -> 2.70e-3 chamfer
  /// (2.89 without the rim), the holed bunny 1.46 -> 1.59 (Poisson 1.82), fandisk unchanged.
  int rim_min_hole_vertices = 20;
  /// The most rings rim_offset adds around a hole.
  int rim_rings = 1;
  /// Fill hole vertices harmonically from their neighbours; false leaves them on the base surface (d = 0).
  bool fill_holes = true;
  /// Then fair the hole vertices' positions (hole_fairing.hpp; ours), with the data-supported
  /// vertices fixed: the order of the Laplacian minimised, 0 off (the harmonic displacements above
  /// only), 1 membrane, 2 thin plate (bi-Laplacian: continues the rim's slope into the hole), 3.
  int hole_fairing = 2;
  /// A hole region with more vertices than this keeps the harmonic fill (0: no limit): a bound on
  /// fairing's cost, whose sparse LU grows faster than the region (Release, 2 cores: 11k vertices 0.5 s,
  /// 20k 3 s, 67k 11 s). The largest holes met so far: 53k vertices (the 6000-point block, 2.4 s).
  int hole_fairing_max_vertices = 100000;
  /// Foot points whose normal makes a larger angle than this (degrees) with the vertex normal are
  /// ignored: on a thin part the other side's data lies within the support but belongs elsewhere.
  double max_normal_angle_deg = 90.0;
  /// Curvature check (paper §3.2): a vertex with |d(v)| >= this x its smaller principal curvature radius
  /// is at risk; the triangles of its one-ring are tested for flips.
  double curvature_factor = 0.5;
  /// Only count a radius when the displacement goes towards its centre of curvature (inward on convex,
  /// outward on concave parts: the paper's "deep convex or concave parts"); moving away from it cannot
  /// make the normals cross. false: compare |d(v)| with the smaller radius whatever the direction.
  bool signed_curvature_check = true;
  /// Residual passes (ours): the Gaussian mean of the d_k is biased wherever d varies across the
  /// filter (a base surface tilted against the data, a corner); each pass measures every point's
  /// remaining offset r_k = (p_k - q'_k) . n_k from the displaced mesh (q'_k: the foot point carried
  /// along with its triangle) and adds the Gaussian mean of the r_k (Van Cittert's iteration). 0: the
  /// paper's single filter. Each pass also lets the noise through a little more.
  int residual_passes = 3;
  /// Noise-free data with the spacing filter (ours; 0 = off): after the residual passes, this many more
  /// with the paper's narrow Gaussian mean (sigma_factor x edge) of the remaining offsets. The wide fit
  /// leaves a crease's kink in the residuals (a plane cannot follow it); on smooth parts it leaves
  /// almost none, so the narrow mean adds almost nothing there and its ripple (the reason for the wide
  /// fit) stays as small as the residuals. A vertex without feet in the narrow support keeps the wide fit.
  int fine_residual_passes = 3;
  /// fine_residual_passes skip a vertex whose narrow support's residuals (after the wide fit) spread
  /// by more than this x the narrow width (weighted RMS about their mean): its feet come from different
  /// sheets of the data (a thin wall Phase 1 blurred), where a narrow mean follows the nearer one.
  /// 0: no limit (default: on fandisk cut 0.1 lowered e_avr of MS further but raised e_max, 9.6 -> 14e-3;
  /// configs/ablation_fine_residual.yaml).
  double fine_max_spread = 0.0;
  /// ...and skip a vertex whose wide fit's |d(v)| exceeds this x the wide width (0: no limit): far from
  /// the data (fandisk's thin wall, |d| ~ 3 widths) the base's feet scatter (as for feature_max_offset).
  double fine_max_offset = 0.5;
  /// Noise along the normal, standard deviation in frame units (ours): -1 estimates it from the data
  /// (noise_estimate.hpp), 0 takes the data as noise-free (the fixed filter above, as before), > 0 is
  /// the user's figure (a scanner's depth noise). Noise widens the filter and stops the residual passes.
  double noise_sigma = -1.0;
  /// An estimated noise below this x the data's median spacing is taken as none (the paper's fixed
  /// filter): the estimate cannot tell such a small figure from unresolved relief. Measured with
  /// bench/noise_estimate: clean data read 0-1.4 % (the 6k bunny 0.25e-3 at spacing 17e-3, the torus
  /// 0.6 %), the torus with noise sigma 1e-3 5.2 %, the noisy 25k models 23-25 %.
  double noise_floor = 0.03;
  /// Where the data are noisy each vertex picks its own filter width (ours), by the intersection of
  /// confidence intervals (ICI; Katkovnik's LPA-ICI): widths sigma x scale_ratio^j, the estimate d_j of
  /// each with its noise deviation s_j = sigma_n sqrt(sum_k l_k^2); the widest j whose intervals
  /// [d_i - ici_threshold s_i, d_i + ici_threshold s_i], i <= j, still share a point. A wider filter
  /// averages more noise away until its bias (the shape it flattens) exceeds the noise it removes;
  /// smooth parts get a wide filter, fine relief keeps the narrow one.
  double ici_threshold = 1.0;
  /// Stop widening at a width whose noise deviation s_j exceeds the narrower one's (ours): ICI assumes
  /// that a wider filter averages more noise away; a one-sided linear fit at a hole's rim, or a filter
  /// over thinned feet, can be wider and noisier, and its wider interval would pass the test.
  bool ici_monotone = false;
  /// One-ring median passes over the widths ICI chose (0: ICI's choice per vertex as it is).
  int ici_smoothing = 4;
  double scale_ratio = 1.41421356237;
  /// Noisy data with more foot points than this x the mesh's vertices: the widths beyond the third
  /// (sigma x scale_ratio^2, twice sigma at the default ratio) take every k-th foot, inner ones included
  /// (k the ratio, rounded up), so their cost stays bounded at 1M points (0: all feet).
  double max_feet_per_vertex = 8.0;
  /// The widest filter tried, x the mean edge length.
  double max_sigma_factor = 4.0;
  /// The filter fits a polynomial of this degree to the d_k over the vertex's tangent plane and takes
  /// its value at the vertex (local polynomial regression; ours): 0 is the paper's Gaussian mean, 1
  /// (linear) is unbiased where d varies linearly (a tilted base surface), 2 (quadratic) where it bends
  /// too, so a filter widened against noise flattens less of the shape. On noisy data only the widened
  /// filters fit (the base width keeps the paper's mean); on noise-free data the base filter does,
  /// unless spacing_sigma_factor is 0 (the paper's filter). A vertex whose feet cannot support the fit
  /// (too few, one-sided at a hole's rim) falls back to the next lower degree.
  int regression_degree = 1;
  /// Residual passes stop once the RMS of the points' remaining offsets falls to this x sigma_n
  /// (Morozov's discrepancy principle: a fit closer than the noise is fitting the noise). 0 (default):
  /// all passes. Off because with the widened filters the passes correct bias, not noise: stopped at
  /// 1.1 sigma_n the noisy test sphere ends twice as far from the truth (tests/displacement).
  double discrepancy = 0.0;
  /// Noise-free data (ours; 0 = the paper's filter): the base filter is at least this x the data's
  /// median spacing wide and fits the regression_degree polynomial. At the paper's width (half an edge,
  /// support 1.5 edges) a vertex sees a few feet where the spacing nears 1.5 edges (fandisk cut:
  /// spacing 0.038, edges 0.025: two to three), so d jumps from vertex to vertex wherever the base
  /// surface is tilted against the data: a ripple at the data's spacing. A wider mean alone flattens the shape
  /// (configs/ablation_displacement_filter.yaml); the linear fit is unbiased where d varies linearly.
  /// configs/ablation_sparse_filter.yaml: at 1 chamfer drops on all four noise-free models (fandisk cut
  /// 8.51 -> 7.73e-3, holed bunny 1.99 -> 1.86, block 2.26 -> 2.07, torus 0.60 -> 0.58). Noisy data
  /// keep their ICI widths (which fit already).
  double spacing_sigma_factor = 1.0;
  /// Fit the data points' heights above v's tangent plane, (p_k - v) . n(v), instead of their
  /// displacements d_k from their feet, wherever the filter fits a polynomial (degree >= 1; ours, off by
  /// default): a moving-least-squares estimate of where the data cross v's normal line, which does not
  /// inherit the base surface's bumps between the feet (a lumpy MI at the T-mesh's cell size, under data
  /// sparser than that). The residual passes then remove the fit's curvature bias. Vertices with a mean
  /// (degree 0) keep the d_k. configs/ablation_displacement_fit.yaml.
  bool fit_heights = false;
  /// Noise-free data with the spacing filter (ours; 0 = off): a vertex whose wide filter's feet do not
  /// fit a quadratic in the tangent plane (weighted RMS misfit of the d_k above this x the wide width:
  /// a crease runs under the filter, and d has a kink no polynomial follows; a quadratic absorbs the
  /// curvature difference of base and data on smooth parts) takes the paper's narrow mean instead
  /// (sigma_factor x edge, degree 0) if its feet pass the hole test: the spacing filter's ripple-free
  /// fit on the smooth parts, the paper's sharper one at the creases, which the wide fit rounds off.
  /// configs/ablation_feature_filter.yaml.
  double feature_misfit = 0.0;
  /// feature_misfit only where the base surface is near the data: the wide fit's |d(v)| below this x
  /// its width. Farther (fandisk cut: a thin wall Phase 1 blurs, |d| ~ 3 sigma) the feet on the base
  /// scatter, and the narrow mean follows them (e_max 2x the wide fit's there).
  double feature_max_offset = 0.5;
  /// The data's median spacing for spacing_sigma_factor, frame units; 0: measured (noise_estimate.hpp).
  double data_spacing = 0.0;
  NoiseEstimateOptions noise;
  /// Test every triangle for flips, not only those around vertices at risk (a diagnostic).
  bool check_all_faces = false;
  /// Report e_avr/e_max of the data against the base and displaced meshes (through MeshLocator's
  /// one-ring search: close to, not exactly, the metrics module's exact distances).
  bool report_errors = true;
  ProjectionOptions projection;

  void visit(FieldVisitor& v) override;
  void check() const override;
};

struct DisplacementResult {
  TriangleMesh mesh;                        ///< the displaced mesh, vertex normals from grad f at the base vertex
  std::vector<double> vertex_displacement;  ///< d(v) per vertex; for a faired hole vertex the normal part of its move
  std::vector<int> hole_vertices;           ///< vertices without data near them: filled, then faired (hole_fairing)
  std::vector<int> at_risk_vertices;        ///< |d(v)| >= curvature_factor x smaller curvature radius
  std::vector<int> feature_vertices;        ///< took the paper's narrow mean (feature_misfit)
  std::vector<int> flipped_faces;           ///< faces whose normal reversed (among those tested)
  std::vector<int> flipped_vertices;        ///< vertices of flipped faces: where to refine the level set
  bool needs_refinement = false;            ///< a flip happened: refine f (final refinement) and redo
  ProjectionResult projection;
  nlohmann::json summary;                   ///< counts, flips, holes, e_avr/e_max before/after, seconds
};

/// Paper §3.1-3.2 on `base` (the initial mesh M_0 of f = 0). Throws ConfigError for invalid options,
/// AlgorithmError for no data points, a non-finite point, or an empty / invalid mesh.
DisplacementResult displace_mesh(const ImplicitFunction& f, const TriangleMesh& base, const std::vector<Vec3>& points,
                                 const DisplacementOptions& options = {});

/// The Phase-2 stage as a plugin.
class Displacer {
 public:
  virtual ~Displacer() = default;
  virtual Options& options() = 0;
  virtual DisplacementResult displace(const ImplicitFunction& f, const TriangleMesh& base,
                                      const std::vector<Vec3>& points) = 0;
};

Registry<Displacer>& displacers();
/// Adds `gaussian` (the paper's Gaussian-filtered displacement with harmonic hole fill). Idempotent.
void register_displacers();

}  // namespace dtsl
