// Paper §3.2: Gaussian-filtered vertex displacements, hole fill, displacement along grad f, flip check.
#include "algorithms/displacement/displacement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <string>

#include "algorithms/displacement/curvature.hpp"
#include "algorithms/displacement/hole_fairing.hpp"
#include "algorithms/displacement/hole_fill.hpp"
#include "algorithms/displacement/hole_rim.hpp"
#include "algorithms/displacement/local_regression.hpp"
#include "algorithms/displacement/vertex_grid.hpp"
#include "framework/config/prefixed_visitor.hpp"
#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"

namespace dtsl {

void DisplacementOptions::visit(FieldVisitor& v) {
  v.field("sigma", sigma, "Gaussian filter width in frame units (0 = sigma_factor x the base mesh's mean edge length)");
  v.field("sigma_factor", sigma_factor, "sigma = sigma_factor x mean edge length (~ delta) when sigma is 0");
  v.field("support", support, "foot points farther than this x sigma from a vertex are ignored");
  v.field("min_points", min_points, "a vertex with fewer foot points within the support is a hole vertex");
  v.field("min_weight", min_weight,
          "a vertex whose Gaussian weights sum to less than this is a hole vertex (its feet are all far)");
  v.field("spike_factor", spike_factor,
          "|d(v) - mean d of its neighbours| above this x the mean edge length: a spike, refilled from the "
          "neighbours (0: off)");
  v.field("rim_offset", rim_offset,
          "a vertex next to a hole whose feet's weighted centroid lies farther than this x the filter width from it "
          "in the tangent plane (feet to one side: an extrapolation) joins the hole (0: off)");
  v.field("rim_rings", rim_rings, "rim_offset: the most rings added around a hole");
  v.field("fill_holes", fill_holes, "fill hole vertices harmonically from their neighbours (false: d = 0 there)");
  v.field("hole_fairing", hole_fairing,
          "then fair the hole vertices' positions with the others fixed: order of the Laplacian minimised (0 off, "
          "1 membrane, 2 thin plate: continues the rim's slope into the hole, 3)");
  v.field("hole_fairing_max_vertices", hole_fairing_max_vertices,
          "a hole region with more vertices than this keeps the harmonic fill (0: no limit; a bound on the "
          "fairing's cost, which grows faster than the region)");
  v.field("max_normal_angle_deg", max_normal_angle_deg,
          "ignore foot points whose normal differs from the vertex normal by more than this (thin parts)");
  v.field("curvature_factor", curvature_factor,
          "|d(v)| >= this x the smaller curvature radius puts v at risk: its one-ring is tested for flips");
  v.field("signed_curvature_check", signed_curvature_check,
          "only radii whose centre lies on the displacement's side count (inward on convex, outward on concave)");
  v.field("residual_passes", residual_passes,
          "passes that add the Gaussian mean of each point's remaining offset from the displaced mesh "
          "(removes the filter's bias where d varies; 0 = the paper's single filter)");
  v.field("fine_residual_passes", fine_residual_passes,
          "noise-free data, spacing filter: further residual passes with the paper's narrow Gaussian mean "
          "(a crease's kink the wide fit leaves; 0 = off)");
  v.field("fine_max_spread", fine_max_spread,
          "fine_residual_passes skip a vertex whose narrow support's residuals spread (RMS) more than this x "
          "the narrow width (feet of different sheets: a thin wall Phase 1 blurred; 0: no limit)");
  v.field("fine_max_offset", fine_max_offset,
          "fine_residual_passes skip a vertex whose wide fit's |d| exceeds this x its width (0: no limit)");
  v.field("rim_min_hole_vertices", rim_min_hole_vertices,
          "rim_offset grows only holes of at least this many connected vertices (smaller: gaps in sparse data)");
  v.field("rim_min_feet", rim_min_feet,
          "rim_offset tests only vertices whose base filter has at least this many feet (fewer: sparse data)");
  v.field("noise_sigma", noise_sigma,
          "noise along the normal (frame units): -1 estimates it from the data, 0 = noise-free, > 0 = given");
  v.field("noise_floor", noise_floor,
          "an estimated noise below this x the data's median spacing counts as none (the fixed filter)");
  v.field("ici_threshold", ici_threshold,
          "noisy data: a vertex widens its filter while the estimates' intervals +- this x their noise deviation intersect");
  v.field("ici_monotone", ici_monotone,
          "noisy data: stop widening at a width whose noise deviation exceeds the narrower one's (one-sided "
          "fits at hole rims, thinned feet)");
  v.field("ici_smoothing", ici_smoothing, "noisy data: one-ring median passes over the widths ICI chose");
  v.field("max_feet_per_vertex", max_feet_per_vertex,
          "noisy data: widened filters use every k-th foot when there are more than this x the vertices (0: all)");
  v.field("scale_ratio", scale_ratio, "noisy data: successive filter widths tried differ by this factor");
  v.field("max_sigma_factor", max_sigma_factor, "noisy data: the widest filter tried, x mean edge length");
  v.field("regression_degree", regression_degree,
          "degree of the local polynomial fitted to the d_k over the tangent plane (0 = the paper's Gaussian mean)");
  v.field("discrepancy", discrepancy,
          "residual passes stop when the points' RMS offset falls to this x the noise sigma (0: all passes)");
  v.field("spacing_sigma_factor", spacing_sigma_factor,
          "noise-free data: the base filter at least this x the data's median spacing wide, and fitting "
          "regression_degree (data sparser than the mesh ripple at the paper's width; 0: the paper's filter)");
  v.field("fit_heights", fit_heights,
          "fit the data's heights above each vertex's tangent plane instead of the d_k where the fit is a "
          "polynomial (the base's bumps between the feet do not carry into the mesh)");
  v.field("feature_misfit", feature_misfit,
          "noise-free data, spacing filter: a vertex whose d_k misfit a quadratic by more than this x the filter's "
          "width (a crease under the filter) takes the paper's narrow mean (0: off)");
  v.field("feature_max_offset", feature_max_offset,
          "feature_misfit: only where the wide fit's |d| is below this x its width (farther, the base's feet scatter)");
  v.field("data_spacing", data_spacing, "the data's median spacing for spacing_sigma_factor (0: measured)");
  {
    PrefixedVisitor n(v, "noise_");
    noise.visit(n);
  }
  v.field("check_all_faces", check_all_faces, "test every triangle for flips, not only around vertices at risk");
  v.field("report_errors", report_errors, "report e_avr/e_max before and after (one-ring search, approximate)");
  projection.visit(v);
}

void DisplacementOptions::check() const {
  check_non_negative("sigma", sigma);
  check_range("sigma_factor", sigma_factor, 0.05, 10.0);
  check_range("support", support, 0.5, 10.0);
  check_range("min_points", min_points, 1, 1000000);
  check_range("min_weight", min_weight, 0.0, 1.0);
  check_non_negative("spike_factor", spike_factor);
  check_range("rim_offset", rim_offset, 0.0, 10.0);
  check_range("rim_rings", rim_rings, 0, 100);
  check_range("rim_min_feet", rim_min_feet, 1, 1000);
  check_range("rim_min_hole_vertices", rim_min_hole_vertices, 1, 100000000);
  check_range("max_normal_angle_deg", max_normal_angle_deg, 0.0, 180.0);
  check_range("curvature_factor", curvature_factor, 0.0, 10.0);
  check_range("residual_passes", residual_passes, 0, 20);
  check_range("fine_residual_passes", fine_residual_passes, 0, 20);
  check_range("fine_max_spread", fine_max_spread, 0.0, 100.0);
  check_range("fine_max_offset", fine_max_offset, 0.0, 100.0);
  check_range("hole_fairing", hole_fairing, 0, 3);
  check_non_negative("hole_fairing_max_vertices", hole_fairing_max_vertices);
  std::ostringstream given;
  given << noise_sigma;
  require(noise_sigma == -1.0 || noise_sigma >= 0.0, "noise_sigma",
          "must be -1 (estimate from the data), 0 (noise-free) or positive, got " + given.str());
  check_range("noise_floor", noise_floor, 0.0, 1.0);
  check_range("ici_threshold", ici_threshold, 0.1, 10.0);
  check_range("scale_ratio", scale_ratio, 1.05, 4.0);
  check_range("ici_smoothing", ici_smoothing, 0, 100);
  check_non_negative("max_feet_per_vertex", max_feet_per_vertex);
  check_range("max_sigma_factor", max_sigma_factor, 0.05, 20.0);
  check_range("regression_degree", regression_degree, 0, 2);
  check_non_negative("discrepancy", discrepancy);
  check_range("spacing_sigma_factor", spacing_sigma_factor, 0.0, 10.0);
  check_non_negative("data_spacing", data_spacing);
  check_range("feature_misfit", feature_misfit, 0.0, 10.0);
  check_range("feature_max_offset", feature_max_offset, 0.0, 100.0);
  checked_with_prefix("noise_", [&] { noise.check(); });
  projection.check();
}

namespace {

// Mean / max distance of the points to the mesh through the one-ring locator.
nlohmann::json onering_errors(const MeshLocator& locator, const std::vector<Vec3>& points) {
  const long n = static_cast<long>(points.size());
  std::vector<double> distance(n);
#pragma omp parallel for schedule(static)
  for (long k = 0; k < n; ++k) distance[k] = locator.locate(points[k]).distance;
  double sum = 0.0, mx = 0.0;  // in point order: the same for every thread count
  for (double d : distance) sum += d, mx = std::max(mx, d);
  return {{"e_avr", sum / static_cast<double>(n)}, {"e_max", mx}};
}

}  // namespace

DisplacementResult displace_mesh(const ImplicitFunction& f, const TriangleMesh& base, const std::vector<Vec3>& points,
                                 const DisplacementOptions& options) {
  options.check();
  if (base.faces.empty() || base.vertices.empty()) throw AlgorithmError("displacement: the base mesh has no faces");
  Stopwatch timer;
  const MeshLocator locator(base, options.projection.locator);
  DisplacementResult r;
  // Paper §3.1: foot points, d_k, closest triangles.
  r.projection = project_data(f, locator, points, options.projection);
  const ProjectionResult& pr = r.projection;

  const std::size_t nv = base.vertices.size();
  const double edge = locator.mean_edge_length();
  double sigma = options.sigma > 0 ? options.sigma : options.sigma_factor * edge;
  const double paper_sigma = sigma;  // the paper's width, for feature vertices (feature_misfit)
  const double cos_max = std::cos(options.max_normal_angle_deg * M_PI / 180.0);

  // The noise along the normal: it sets how many feet a vertex's filter must average.
  Stopwatch part;
  NoiseEstimate noise;
  // Fewer points than a fit needs: no estimate, the fixed filter (the summary says so).
  const bool can_estimate = points.size() >= static_cast<std::size_t>(options.noise.neighbours);
  const bool estimate = options.noise_sigma < 0 && can_estimate;
  if (estimate) noise = estimate_noise(points, options.noise);
  const double noise_sigma = options.noise_sigma >= 0                              ? options.noise_sigma
                             : noise.sigma >= options.noise_floor * noise.spacing ? noise.sigma
                                                                                  : 0.0;
  const double noise_seconds = part.seconds();
  // Noise-free data sparser than the mesh (ours, spacing_sigma_factor): a base filter as wide as the
  // spacing, fitting a polynomial so that the wider filter does not flatten where d varies.
  double spacing = options.data_spacing;
  if (options.spacing_sigma_factor > 0 && noise_sigma == 0 && spacing <= 0 && can_estimate)
    spacing = estimate ? noise.spacing : estimate_noise(points, options.noise).spacing;
  const bool base_fit = options.spacing_sigma_factor > 0 && spacing > 0 && noise_sigma == 0;
  if (base_fit) sigma = std::max(sigma, options.spacing_sigma_factor * spacing);
  // Filter widths tried where the data are noisy (ICI, DisplacementOptions::ici_threshold).
  std::vector<double> widths{sigma};
  if (noise_sigma > 0)
    while (widths.back() * options.scale_ratio <= options.max_sigma_factor * edge * (1 + 1e-9))
      widths.push_back(widths.back() * options.scale_ratio);
  const bool widen = widths.size() > 1;
  std::vector<double> support2;  // squared support radius of each width
  for (double w : widths) support2.push_back(std::pow(options.support * w, 2));
  const double radius = options.support * widths.back();

  // Only converged, located foot points carry the field.
  std::vector<Vec3> feet;
  std::vector<int> foot_id;
  std::size_t valid = 0;
  for (std::size_t k = 0; k < pr.foot_points.size(); ++k) valid += pr.valid[k] ? 1 : 0;
  if (valid == 0) throw AlgorithmError("displacement: no data point could be projected onto f = 0");
  for (std::size_t k = 0; k < pr.foot_points.size(); ++k)
    if (pr.valid[k]) feet.push_back(pr.foot_points[k]), foot_id.push_back(static_cast<int>(k));
  // Cells about half the query radius: a widened filter's ball (up to 8x the base radius) would
  // otherwise visit thousands of empty cells per vertex. Most vertices stop widening early, so their
  // feet are first gathered for the first few widths only (`near`), from a finer grid.
  const std::size_t near = std::min<std::size_t>(2, widths.size() - 1);
  const PointGrid foot_grid(feet, 0.5 * options.support * widths[near] * (widen ? 1.0 : 2.0));
  // The widths beyond `near` on dense data: every stride-th foot only (in point order: deterministic).
  // A filter 4 edges wide would otherwise gather thousands of feet per vertex at 1M points, where a
  // few hundred already put the noise's share far below the noise (the ICI weighs what it gets).
  const double per_vertex_cap = options.max_feet_per_vertex * static_cast<double>(nv);
  const std::size_t stride =
      options.max_feet_per_vertex > 0 && static_cast<double>(valid) > per_vertex_cap
          ? static_cast<std::size_t>(std::ceil(static_cast<double>(valid) / per_vertex_cap))
          : 1;
  std::vector<Vec3> far_feet;
  std::vector<int> far_foot_id;
  std::unique_ptr<PointGrid> far_grid;
  if (near + 1 < widths.size()) {
    for (std::size_t i = 0; i < feet.size(); i += stride) far_feet.push_back(feet[i]), far_foot_id.push_back(foot_id[i]);
    far_grid = std::make_unique<PointGrid>(far_feet, 0.5 * radius);
  }

  // Vertex normals from grad f (paper §3.2), and the Gaussian-weighted mean of the nearby d_k. The
  // neighbourhood is a Euclidean ball around v over the foot points (all on f = 0), which for
  // sigma << the curvature radii is the geodesic one the paper's per-triangle lists I_i describe; the
  // normal test keeps the other side of a thin part out. The lists I_i stay in the result for Phase 3.
  std::vector<Vec3> normals(nv);
  std::vector<char> known(nv, 0);
  std::vector<PrincipalCurvatures> curv(nv);
  std::vector<double> vertex_sigma(nv, sigma);
  std::vector<int> degree_used(nv, 0), width_index(nv, 0);
  // The base filter's one-sidedness: |tangential part of its feet's weighted centroid - v| / width
  // (rim_offset).
  std::vector<double> centroid_shift(nv, 0.0);
  // Per vertex, the foot points of its filter and their weights, normalised to sum 1.
  std::vector<std::vector<std::pair<int, double>>> filter(nv);
  // v's feet within the widest support that pass the normal test: (point, squared distance).
  const auto gather = [&](long v, std::vector<std::pair<int, double>>& reach, std::size_t upto) {
    reach.clear();
    const bool far = upto > near;
    const PointGrid& grid = far ? *far_grid : foot_grid;
    const std::vector<int>& ids = far ? far_foot_id : foot_id;
    grid.for_each_within(base.vertices[v], options.support * widths[upto], [&](int i, double d2) {
      const int k = ids[i];
      if (pr.foot_normals[k].dot(normals[v]) < cos_max) return;
      reach.emplace_back(k, d2);
    });
    // Widened: grouped by the narrowest width whose support holds them (a counting sort, stable, so
    // the order stays the grid's: deterministic), so that each width's taps are a prefix.
    if (widen) {
      std::vector<int> group(reach.size());
      std::vector<std::size_t> start(widths.size() + 1, 0);
      for (std::size_t t = 0; t < reach.size(); ++t) {
        const std::size_t j = static_cast<std::size_t>(
            std::lower_bound(support2.begin(), support2.end(), reach[t].second) - support2.begin());
        group[t] = static_cast<int>(std::min(j, widths.size() - 1));
        ++start[group[t] + 1];
      }
      for (std::size_t j = 1; j < start.size(); ++j) start[j] += start[j - 1];
      std::vector<std::pair<int, double>> sorted(reach.size());
      for (std::size_t t = 0; t < reach.size(); ++t) sorted[start[group[t]]++] = reach[t];
      reach.swap(sorted);
    }
  };
  // Width j's taps: the feet within its support (sigma_j, or `narrow`'s), Gaussian weights normalised
  // to sum 1; false where they fail the hole test.
  const auto gaussian_taps = [&](const std::vector<std::pair<int, double>>& reach, double sv, double keep2,
                                 std::vector<std::pair<int, double>>& out) {
    const double inv2s2 = 1.0 / (2.0 * sv * sv);
    out.clear();
    double wsum = 0.0;
    for (const auto& [k, d2] : reach) {
      if (d2 > keep2) {
        if (widen) break;  // grouped by width: the rest lie beyond this one
        continue;
      }
      const double w = std::exp(-d2 * inv2s2);
      wsum += w;
      out.emplace_back(k, w);
    }
    if (static_cast<int>(out.size()) < options.min_points || !(wsum > 0) || wsum < options.min_weight) return false;
    // A fixed summation order: the same d whatever the threads (widened: the width-group, then grid-cell
    // order of `reach` already is).
    if (!widen) std::sort(out.begin(), out.end());
    for (auto& tap : out) tap.second /= wsum;
    return true;
  };
  const bool detect_features = base_fit && options.feature_misfit > 0 && paper_sigma < sigma;
  std::vector<char> feature(nv, 0);
  // Width j's taps, with polynomial weights beyond the paper's mean (widened or spacing filter), or the
  // paper's narrow mean at a crease (feature_misfit).
  const auto taps_at = [&](long v, const std::vector<std::pair<int, double>>& reach, std::size_t j,
                           std::vector<std::pair<int, double>>& out, int* degree) {
    const double sv = widths[j];
    if (!gaussian_taps(reach, sv, support2[j], out)) return false;
    if (j == 0 && options.rim_offset > 0) {
      Vec3 centroid = Vec3::Zero();
      for (const auto& [k, w] : out) centroid += w * (pr.foot_points[k] - base.vertices[v]);
      centroid -= centroid.dot(normals[v]) * normals[v];
      centroid_shift[v] = static_cast<int>(out.size()) >= options.rim_min_feet ? centroid.norm() / sv : 0.0;
    }
    // The misfit of a quadratic, on the Gaussian weights: it absorbs the curvature difference of base and
    // data on smooth parts, not a crease's kink (a plane's misfit flagged the bunny's curved parts too).
    const bool crease = j == 0 && detect_features &&
                        local_regression_misfit(out, pr.foot_points, pr.displacements, base.vertices[v], normals[v],
                                                sv, 2) > options.feature_misfit * sv;
    *degree = (j > 0 || base_fit) && options.regression_degree > 0
                  ? local_regression_weights(out, pr.foot_points, base.vertices[v], normals[v], sv,
                                             options.regression_degree)
                  : 0;
    if (crease) {
      double wide = 0.0;  // d(v) from the spacing filter's fit
      for (const auto& [k, w] : out) wide += w * pr.displacements[k];
      std::vector<std::pair<int, double>> narrow;
      if (std::abs(wide) < options.feature_max_offset * sv &&
          gaussian_taps(reach, paper_sigma, std::pow(options.support * paper_sigma, 2), narrow)) {
        out.swap(narrow);
        feature[v] = 1;
        *degree = 0;
      }
    }
    return true;
  };
#pragma omp parallel for schedule(dynamic, 256)
  for (long v = 0; v < static_cast<long>(nv); ++v) {
    Vec3 g;
    Mat3 H;
    f.evaluate(base.vertices[v], &g, &H);
    const double gn = g.norm();
    normals[v] = gn > 0 && g.allFinite() ? Vec3(g / gn)
                 : base.has_normals()     ? base.normals[v]
                                          : Vec3::Zero();
    curv[v] = principal_curvatures(g, H);
    std::vector<std::pair<int, double>>& taps = filter[v];
    std::vector<std::pair<int, double>> reach;
    gather(v, reach, near);
    std::size_t reached = near;  // reach holds the feet of widths 0..reached
    int degree = 0;
    if (!taps_at(v, reach, 0, taps, &degree)) {
      taps.clear();
      continue;
    }
    known[v] = 1;
    degree_used[v] = degree;
    if (feature[v]) vertex_sigma[v] = paper_sigma;
    // ICI: widen while the confidence intervals of the estimates so far intersect.
    const auto estimate = [&](const std::vector<std::pair<int, double>>& t, double* deviation) {
      double e = 0.0, l2 = 0.0;
      for (const auto& [k, l] : t) e += l * pr.displacements[k], l2 += l * l;
      *deviation = options.ici_threshold * noise_sigma * std::sqrt(l2);
      return e;
    };
    double dev = 0.0, e = estimate(taps, &dev);
    double lower = e - dev, upper = e + dev;
    std::vector<std::pair<int, double>> wider;
    for (std::size_t j = 1; j < widths.size(); ++j) {
      if (j > reached) gather(v, reach, reached = widths.size() - 1);
      if (!taps_at(v, reach, j, wider, &degree)) break;
      const double narrower_dev = dev;
      e = estimate(wider, &dev);
      if (options.ici_monotone && dev > narrower_dev) break;
      lower = std::max(lower, e - dev), upper = std::min(upper, e + dev);
      if (lower > upper) break;
      taps.swap(wider);
      width_index[v] = static_cast<int>(j);
      degree_used[v] = degree;
      vertex_sigma[v] = widths[j];
    }
  }
  // The chosen widths, smoothed: each vertex takes the median index of its one-ring (ICI's choices
  // jump between neighbours; a patchwork of widths is a patchwork of biases). Then the taps again.
  if (widen && options.ici_smoothing > 0) {
    const std::vector<int> chosen = width_index;
    for (int pass = 0; pass < options.ici_smoothing; ++pass) {
      std::vector<int> next = width_index;
#pragma omp parallel for schedule(static)
      for (long v = 0; v < static_cast<long>(nv); ++v) {
        if (!known[v]) continue;
        std::vector<int> ring{width_index[v]};
        for (int u : locator.vertex_neighbours(static_cast<int>(v)))
          if (known[u]) ring.push_back(width_index[u]);
        std::nth_element(ring.begin(), ring.begin() + static_cast<long>(ring.size() / 2), ring.end());
        next[v] = ring[ring.size() / 2];
      }
      width_index.swap(next);
    }
#pragma omp parallel for schedule(dynamic, 256)
    for (long v = 0; v < static_cast<long>(nv); ++v) {
      if (!known[v] || width_index[v] == chosen[v]) continue;  // its taps are those of its width
      std::vector<std::pair<int, double>> reach, taps;
      gather(v, reach, static_cast<std::size_t>(width_index[v]));
      // A width whose taps fail the hole test (thinned feet can weigh less than min_weight): the next narrower,
      // from all the feet again once it is one of the `near` widths.
      for (int j = width_index[v]; j >= 0; --j) {
        if (static_cast<std::size_t>(j) == near && static_cast<std::size_t>(width_index[v]) > near) gather(v, reach, near);
        int degree = 0;
        if (taps_at(v, reach, static_cast<std::size_t>(j), taps, &degree)) {
          filter[v].swap(taps);
          degree_used[v] = degree;
          vertex_sigma[v] = widths[j];
          break;
        }
      }
    }
  }
  const double filter_seconds = part.seconds() - noise_seconds;
  const auto filtered = [&](const std::vector<double>& value, std::vector<double>& d) {
#pragma omp parallel for schedule(static)
    for (long v = 0; v < static_cast<long>(nv); ++v) {
      double sum = 0.0;
      for (const auto& [k, w] : filter[v]) sum += w * value[k];
      d[v] += sum;
    }
  };
  std::vector<double> d(nv, 0.0);
  if (options.fit_heights) {
    // The data's heights above v's tangent plane, h_k = (p_k - v) . n(v) with p_k = q_k + d_k n_k, in
    // place of the d_k where the fit is a polynomial: the base surface's own bumps between the feet
    // ((q_k - v) . n(v) != 0) then do not carry into the mesh. A mean (degree 0) of heights would sink
    // by the curvature times the filter's spread: those vertices keep the d_k.
#pragma omp parallel for schedule(static)
    for (long v = 0; v < static_cast<long>(nv); ++v) {
      const bool heights = degree_used[v] >= 1;
      double sum = 0.0;
      for (const auto& [k, w] : filter[v])
        sum += w * (heights ? pr.displacements[k] * pr.foot_normals[k].dot(normals[v]) +
                                  (pr.foot_points[k] - base.vertices[v]).dot(normals[v])
                            : pr.displacements[k]);
      d[v] = sum;
    }
  } else {
    filtered(pr.displacements, d);
  }
  // Residual passes: the offset each point still has from the displaced mesh, along its foot normal.
  std::vector<double> residual(points.size(), 0.0);
  const auto residuals = [&] {  // fills `residual`; returns their RMS (in point order: thread-independent)
#pragma omp parallel for schedule(static)
    for (long k = 0; k < static_cast<long>(points.size()); ++k) {
      residual[k] = 0.0;
      if (!pr.valid[k]) continue;
      const MeshLocation& loc = pr.locations[k];
      const Face& face = base.faces[loc.face];
      Vec3 moved = Vec3::Zero();
      for (int c = 0; c < 3; ++c) moved += loc.barycentric[c] * (base.vertices[face[c]] + d[face[c]] * normals[face[c]]);
      residual[k] = (points[k] - moved).dot(pr.foot_normals[k]);
    }
    double sum2 = 0.0;
    std::size_t count = 0;
    for (std::size_t k = 0; k < points.size(); ++k)
      if (pr.valid[k]) sum2 += residual[k] * residual[k], ++count;
    return count ? std::sqrt(sum2 / static_cast<double>(count)) : 0.0;
  };
  int passes = 0;
  double residual_rms = -1.0;  // of the final mesh, once measured
  const double discrepancy_rms = options.discrepancy * noise_sigma;
  for (; passes < options.residual_passes; ++passes) {
    residual_rms = residuals();
    if (discrepancy_rms > 0 && residual_rms <= discrepancy_rms) break;
    filtered(residual, d);
    residual_rms = -1.0;
  }
  // Fine residual passes (fine_residual_passes): the paper's narrow mean of what the wide fit left.
  int fine_passes = 0;
  std::size_t fine_vertices = 0;
  if (base_fit && options.fine_residual_passes > 0 && paper_sigma < sigma) {
    std::vector<std::vector<std::pair<int, double>>> narrow(nv);
#pragma omp parallel for schedule(dynamic, 256)
    for (long v = 0; v < static_cast<long>(nv); ++v) {
      // A feature vertex (feature_misfit) has the narrow mean already.
      if (!known[v] || feature[v] || (options.fine_max_offset > 0 && std::abs(d[v]) > options.fine_max_offset * sigma))
        continue;
      std::vector<std::pair<int, double>> reach;
      gather(v, reach, 0);
      if (!gaussian_taps(reach, paper_sigma, std::pow(options.support * paper_sigma, 2), narrow[v])) narrow[v].clear();
    }
    // Where the residuals under a vertex's narrow support disagree (weighted RMS about their mean above
    // fine_max_spread x the narrow width), the feet there come from different sheets of the data, not
    // from one side of a crease: a thin wall Phase 1 blurred, whose feet on the base interleave. A
    // narrow mean there follows whichever sheet is nearer; the vertex keeps the wide fit.
    residuals();
#pragma omp parallel for schedule(static)
    for (long v = 0; v < static_cast<long>(options.fine_max_spread > 0 ? nv : 0); ++v) {
      double mean = 0.0, mean2 = 0.0;
      for (const auto& [k, w] : narrow[v]) mean += w * residual[k], mean2 += w * residual[k] * residual[k];
      if (std::sqrt(std::max(0.0, mean2 - mean * mean)) > options.fine_max_spread * paper_sigma) narrow[v].clear();
    }
    for (const auto& taps : narrow) fine_vertices += taps.empty() ? 0 : 1;
    filter.swap(narrow);  // `filtered` applies `filter`; the wide taps are back after the passes
    for (; fine_vertices > 0 && fine_passes < options.fine_residual_passes; ++fine_passes) {
      if (fine_passes > 0) residuals();
      filtered(residual, d);
    }
    filter.swap(narrow);
  }
  if (noise_sigma > 0 && residual_rms < 0) residual_rms = residuals();  // the summary's figure
  // A hole's rim (rim_offset): the vertices beside it whose feet lie to one side join it, ring by ring.
  // Before the spike test, so that only the weight test's holes seed it and the spike test's neighbour
  // means leave out the extrapolated d it discards.
  std::size_t rim_vertices = 0;
  if (options.rim_offset > 0) {
    const std::vector<int> rim = grow_hole_rims(locator.vertex_neighbours(), centroid_shift, options.rim_offset,
                                                options.rim_rings, options.rim_min_hole_vertices, known);
    for (int v : rim) feature[v] = 0, d[v] = 0.0;
    rim_vertices = rim.size();
  }
  // Spikes: a vertex far off the mean of its neighbours is refilled from them with the holes.
  std::size_t spikes = 0;
  if (options.spike_factor > 0.0) {
    const double limit = options.spike_factor * locator.mean_edge_length();
    std::vector<char> spike(nv, 0);
    for (std::size_t v = 0; v < nv; ++v) {
      if (!known[v]) continue;
      double sum = 0.0;
      int count = 0;
      for (int u : locator.vertex_neighbours(static_cast<int>(v)))
        if (known[u]) sum += d[u], ++count;
      if (count > 0 && std::abs(d[v] - sum / count) > limit) spike[v] = 1;
    }
    for (std::size_t v = 0; v < nv; ++v)
      if (spike[v]) known[v] = 0, feature[v] = 0, d[v] = 0.0, ++spikes;
  }
  for (std::size_t v = 0; v < nv; ++v)
    if (!known[v]) r.hole_vertices.push_back(static_cast<int>(v));

  // Holes: harmonic fill so the displaced surface continues across without a crease at the rim.
  HoleFillReport fill;
  if (options.fill_holes && !r.hole_vertices.empty()) fill = harmonic_fill(locator.vertex_neighbours(), known, d);

  // Eq. 2: v <- v + d(v) n(v).
  r.mesh = base;
  r.mesh.normals = normals;
  for (std::size_t v = 0; v < nv; ++v) r.mesh.vertices[v] = base.vertices[v] + d[v] * normals[v];
  // Holes, faired (ours): the harmonic fill keeps the base surface's shape in a hole; fairing continues
  // the displaced rim's slope instead. d becomes the normal part of each faired vertex's move.
  HoleFairingReport fairing;
  double fairing_seconds = 0.0;
  std::string fairing_error;
  if (options.fill_holes && options.hole_fairing > 0 && !r.hole_vertices.empty()) {
    Stopwatch fair_timer;
    std::vector<char> free(nv, 0);
    for (int v : r.hole_vertices) free[v] = 1;
    try {
      fairing = fair_holes(r.mesh, free, locator.vertex_neighbours(), options.hole_fairing - 1,
                           static_cast<std::size_t>(options.hole_fairing_max_vertices));
      for (int v : r.hole_vertices) d[v] = (r.mesh.vertices[v] - base.vertices[v]).dot(normals[v]);
    } catch (const AlgorithmError& e) {  // a base mesh CGAL cannot take: the harmonic fill stays, and says so
      fairing_error = e.what();
    }
    fairing_seconds = fair_timer.seconds();
  }
  r.vertex_displacement = d;

  // Curvature check (paper §3.2): vertices whose |d| approaches the smaller radius; flips in their one-ring.
  std::vector<char> candidate(base.faces.size(), 0);
  for (std::size_t v = 0; v < nv; ++v) {
    // d k_i = -1 where v reaches the centre of curvature i (k > 0 convex, n outward).
    const PrincipalCurvatures& c = curv[v];
    const double reach = !c.valid ? 0.0
                         : options.signed_curvature_check
                             ? std::max({-d[v] * c.k1, -d[v] * c.k2, 0.0})
                             : std::abs(d[v]) * std::max(std::abs(c.k1), std::abs(c.k2));
    if (reach > 0 && reach >= options.curvature_factor) {
      r.at_risk_vertices.push_back(static_cast<int>(v));
      for (int fi : locator.vertex_faces(static_cast<int>(v))) candidate[fi] = 1;
    }
  }
  if (fairing.vertices > 0)  // faired vertices also move tangentially: their faces are tested too
    for (int v : r.hole_vertices)
      for (int fi : locator.vertex_faces(v)) candidate[fi] = 1;
  std::vector<int> candidates;
  for (std::size_t fi = 0; fi < candidate.size(); ++fi)
    if (candidate[fi]) candidates.push_back(static_cast<int>(fi));
  r.flipped_faces = flipped_faces(base, r.mesh.vertices, options.check_all_faces ? nullptr : &candidates);
  std::vector<char> fv(nv, 0);
  for (int fi : r.flipped_faces)
    for (int k = 0; k < 3; ++k) fv[base.faces[fi][k]] = 1;
  for (std::size_t v = 0; v < nv; ++v)
    if (fv[v]) r.flipped_vertices.push_back(static_cast<int>(v));
  r.needs_refinement = !r.flipped_faces.empty();
  for (std::size_t v = 0; v < nv; ++v)
    if (feature[v]) r.feature_vertices.push_back(static_cast<int>(v));

  double dmax = 0.0, dmean = 0.0;
  for (double x : d) dmax = std::max(dmax, std::abs(x)), dmean += std::abs(x);
  nlohmann::json s = {{"method", "gaussian"},
                      {"points", points.size()},
                      {"vertices", nv},
                      {"faces", base.faces.size()},
                      {"sigma", sigma},
                      {"data_spacing", spacing},
                      {"base_filter_fits", base_fit},
                      {"residual_passes", passes},
                      {"fine_residual_passes", fine_passes},
                      {"fine_residual_vertices", fine_vertices},
                      {"noise_sigma", noise_sigma},
                      {"noise_estimated", estimate},
                      {"filter_widened", widen},
                      {"feet_stride", far_grid ? stride : 1},
                      {"filter_widths", widths},
                      {"projection", pr.summary()},
                      {"hole_vertices", r.hole_vertices.size()},
                      {"hole_rim_vertices", rim_vertices},
                      {"spike_vertices", spikes},
                      {"hole_vertices_filled", options.fill_holes ? fill.unknown - fill.unreached : 0},
                      {"hole_vertices_unreached", fill.unreached},
                      {"hole_vertices_faired", fairing.vertices},
                      {"hole_regions_faired", fairing.regions},
                      {"hole_fairing_failures", fairing.failed_regions},
                      {"hole_regions_weakly_anchored", fairing.weakly_anchored_regions},
                      {"hole_regions_too_large", fairing.oversized_regions},
                      {"hole_region_max_vertices", fairing.largest_region},
                      {"hole_fairing_seconds", fairing_seconds},
                      {"displacement_mean_abs", dmean / static_cast<double>(nv)},
                      {"displacement_max_abs", dmax},
                      {"at_risk_vertices", r.at_risk_vertices.size()},
                      {"faces_tested_for_flips", options.check_all_faces ? base.faces.size() : candidates.size()},
                      {"flipped_faces", r.flipped_faces.size()},
                      {"flipped_vertices", r.flipped_vertices.size()},
                      {"needs_refinement", r.needs_refinement}};
  if (estimate) s["noise_estimate"] = noise.summary();
  if (!fairing_error.empty()) s["hole_fairing_skipped"] = fairing_error;
  s["noise_seconds"] = noise_seconds;
  s["filter_seconds"] = filter_seconds;
  if (noise_sigma > 0) s["residual_rms"] = residual_rms, s["discrepancy_rms"] = discrepancy_rms;
  {
    double smean = 0.0, smax = 0.0;
    int degrees[3] = {0, 0, 0}, filtered_vertices = 0;
    for (std::size_t v = 0; v < nv; ++v) {
      if (!known[v]) continue;  // hole vertices have no filter
      smean += vertex_sigma[v], smax = std::max(smax, vertex_sigma[v]);
      ++degrees[degree_used[v]], ++filtered_vertices;
    }
    s["vertex_sigma_mean"] = filtered_vertices ? smean / filtered_vertices : sigma;
    s["vertex_sigma_max"] = smax;
    s["regression_degree_vertices"] = {degrees[0], degrees[1], degrees[2]};
    s["feature_vertices"] = r.feature_vertices.size();
  }
  s["seconds"] = timer.seconds();  // the D-Map time of Table 1, without the error report below
  if (options.report_errors) {
    s["errors_before"] = onering_errors(locator, points);
    const MeshLocator after(r.mesh, options.projection.locator);
    s["errors_after"] = onering_errors(after, points);
  }
  r.summary = std::move(s);
  return r;
}

namespace {

class GaussianDisplacer final : public Displacer {
 public:
  Options& options() override { return options_; }
  DisplacementResult displace(const ImplicitFunction& f, const TriangleMesh& base,
                              const std::vector<Vec3>& points) override {
    return displace_mesh(f, base, points, options_);
  }

 private:
  DisplacementOptions options_;
};

}  // namespace

Registry<Displacer>& displacers() {
  static Registry<Displacer> registry("displacer");
  return registry;
}

void register_displacers() {
  Registry<Displacer>& r = displacers();
  if (!r.contains("gaussian"))
    r.add("gaussian",
          "paper §3: Newton foot points, Gaussian-filtered displacements along grad f, harmonic hole fill, flip check",
          [] { return std::make_unique<GaussianDisplacer>(); });
}

}  // namespace dtsl
