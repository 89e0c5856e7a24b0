// Paper §3.2: filtered vertex displacements, hole fill, displacement along grad f, flip check.
#include "algorithms/displacement/displacement.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "algorithms/displacement/curvature.hpp"
#include "algorithms/displacement/flip_check.hpp"
#include "algorithms/displacement/hole_rim.hpp"
#include "algorithms/displacement/hole_treatment.hpp"
#include "algorithms/displacement/residual_passes.hpp"
#include "algorithms/displacement/spikes.hpp"
#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"

namespace dtsl {

namespace {

// The hole rim grows only holes of at least this many connected vertices: on sparse data the weight
// test leaves gaps of a vertex or two, which have no rim. configs/ablation_rim_min_hole.yaml: 20 against
// 1 (every gap) lowered the 10k noisy armadillo sample's chamfer 3.85 -> 2.70e-3, the holed bunny's rose
// 1.46 -> 1.59; 60 lost on both (2.89, 1.67) and the diplodocus (0.86 -> 1.03). The gaps between sparse
// data that DisplacementOptions::gaps makes holes are often larger and grow rims like any hole (the
// rocker arm's D-Map record: hole_rim_vertices 967 with `fit`, 3081 with `margin`,
// results/fig1_rocker_arm/{cross,gaps}).
constexpr int kRimMinHoleVertices = 20;
// One ring of rim vertices: configs/ablation_hole_rim.yaml, three rings raised fandisk cut's chamfer
// 6.65 -> 7.50e-3 and the bunny's e_max of MS 12.0 -> 26.4e-3.
constexpr int kRimRings = 1;
// A vertex whose d differs from its neighbours' mean by more than this x the mean edge length is a
// spike (spikes.hpp); real corners stay below ~1.
constexpr double kSpikeEdges = 3.0;

std::string names_of(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

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

// Normals from grad f (paper §3.2) and principal curvatures at the base vertices.
void vertex_geometry(const ImplicitFunction& f, const TriangleMesh& base, std::vector<Vec3>& normals,
                     std::vector<PrincipalCurvatures>& curvatures) {
  const long nv = static_cast<long>(base.vertices.size());
  normals.assign(nv, Vec3::Zero());
  curvatures.assign(nv, PrincipalCurvatures{});
#pragma omp parallel for schedule(dynamic, 256)
  for (long v = 0; v < nv; ++v) {
    Vec3 g;
    Mat3 H;
    f.evaluate(base.vertices[v], &g, &H);
    const double gn = g.norm();
    normals[v] = gn > 0 && g.allFinite() ? Vec3(g / gn) : base.has_normals() ? base.normals[v] : Vec3::Zero();
    curvatures[v] = principal_curvatures(g, H);
  }
}

// The hole vertices: no data within the filter's support, a hole's one-sided rim (rim_offset), spikes.
// Rim before spikes, so that only the weight test's holes seed it and the spike test's neighbour means
// leave out the extrapolated d it discards.
std::vector<int> hole_vertices(const MeshLocator& locator, const VertexFilters& filters, double rim_offset,
                               std::vector<char>& known, std::vector<double>& d, nlohmann::json& s) {
  std::size_t rim = 0;
  if (rim_offset > 0) {
    const std::vector<int> grown = grow_hole_rims(locator.vertex_neighbours(), filters.one_sidedness, rim_offset,
                                                  kRimRings, kRimMinHoleVertices, known);
    for (int v : grown) d[v] = 0.0;
    rim = grown.size();
  }
  const std::vector<int> spikes =
      find_spikes(locator.vertex_neighbours(), known, d, kSpikeEdges * locator.mean_edge_length());
  for (int v : spikes) known[v] = 0, d[v] = 0.0;
  std::vector<int> holes;
  for (std::size_t v = 0; v < known.size(); ++v)
    if (!known[v]) holes.push_back(static_cast<int>(v));
  s["hole_vertices"] = holes.size();
  s["hole_rim_vertices"] = rim;
  s["spike_vertices"] = spikes.size();
  return holes;
}

// The filter's record: widths, degrees (over the vertices that kept their filter: `known`), noise.
void describe_filter(const VertexFilters& filters, const std::vector<char>& known, const DataScale& scale,
                     bool measured, nlohmann::json& s) {
  s["sigma"] = filters.base_width;
  s["data_spacing"] = scale.spacing;
  s["base_filter_fits"] = filters.base_fits;
  s["noise_sigma"] = scale.noise_sigma;
  s["noise_estimated"] = measured && scale.estimate.has_value();
  s["filter_widened"] = filters.feet->widened();
  s["feet_stride"] = filters.feet->stride();
  s["filter_widths"] = filters.feet->widths();
  if (measured && scale.estimate) s["noise_estimate"] = scale.estimate->summary();
  double smean = 0.0, smax = 0.0;
  int degrees[3] = {0, 0, 0}, filtered_vertices = 0;
  for (std::size_t v = 0; v < known.size(); ++v) {
    if (!known[v]) continue;  // hole vertices have no filter
    smean += filters.width[v], smax = std::max(smax, filters.width[v]);
    ++degrees[filters.degree[v]], ++filtered_vertices;
  }
  s["vertex_sigma_mean"] = filtered_vertices ? smean / filtered_vertices : filters.base_width;
  s["vertex_sigma_max"] = smax;
  s["regression_degree_vertices"] = {degrees[0], degrees[1], degrees[2]};
}

void describe_result(const DisplacementResult& r, std::size_t faces_tested, nlohmann::json& s) {
  double dmax = 0.0, dmean = 0.0;
  for (double x : r.vertex_displacement) dmax = std::max(dmax, std::abs(x)), dmean += std::abs(x);
  s["displacement_mean_abs"] = dmean / static_cast<double>(r.vertex_displacement.size());
  s["displacement_max_abs"] = dmax;
  s["at_risk_vertices"] = r.at_risk_vertices.size();
  s["faces_tested_for_flips"] = faces_tested;
  s["flipped_faces"] = r.flipped_faces.size();
  s["flipped_vertices"] = r.flipped_vertices.size();
  s["needs_refinement"] = r.needs_refinement;
}

}  // namespace

void DisplacementOptions::visit(FieldVisitor& v) {
  v.field("filter", filter,
          "the displacement filter: adaptive (ours: ICI widths on noisy data, a plane over the data's spacing on "
          "noise-free data) or gaussian (the paper's mean)");
  v.field("sigma_factor", sigma_factor,
          "the paper's Gaussian width x the mean edge length (gaussian's width, adaptive's narrowest)");
  v.field("residual_passes", residual_passes,
          "passes that add the filtered remaining offset of each point from the displaced mesh "
          "(removes the filter's bias where d varies; 0 = the paper's single filter)");
  v.field("fine_residual_passes", fine_residual_passes,
          "adaptive filter, noise-free data: further residual passes with the paper's narrow mean "
          "(a crease's kink the plane fit leaves; 0 = off)");
  v.field("hole_fill", hole_fill,
          "what fills vertices without data: thin_plate (the rim's slope continues), membrane or harmonic");
  v.field("rim_offset", rim_offset,
          "a vertex next to a hole whose feet's weighted centroid lies farther than this x the filter width from it "
          "in the tangent plane (feet to one side: an extrapolation) joins the hole (0: off)");
  v.field("gaps", gaps,
          "adaptive filter, noise-free data: vertices with no data within the paper's width are fit (the wide "
          "plane fit) or margin (holes, faired, except within the wide fit's reach of a hole in the data)");
}

void DisplacementOptions::check() const {
  require(displacement_filters().contains(filter), "filter",
          "must be one of " + names_of(displacement_filters().names()) + ", got '" + filter + "'");
  check_range("sigma_factor", sigma_factor, 0.05, 10.0);
  check_range("residual_passes", residual_passes, 0, 20);
  check_range("fine_residual_passes", fine_residual_passes, 0, 20);
  require(hole_treatments().contains(hole_fill), "hole_fill",
          "must be one of " + names_of(hole_treatments().names()) + ", got '" + hole_fill + "'");
  check_range("rim_offset", rim_offset, 0.0, 10.0);
  const std::vector<std::string> gaps_names(std::begin(kSparseGapsNames), std::end(kSparseGapsNames));
  require(sparse_gaps_from_name(gaps).has_value(), "gaps",
          "must be one of " + names_of(gaps_names) + ", got '" + gaps + "'");
}

DisplacementResult displace_mesh(const ImplicitFunction& f, const TriangleMesh& base, const std::vector<Vec3>& points,
                                 const DisplacementOptions& options, const DataScale* scale) {
  options.check();
  if (base.faces.empty() || base.vertices.empty()) throw AlgorithmError("displacement: the base mesh has no faces");
  Stopwatch timer;
  const MeshLocator locator(base);
  DisplacementResult r;
  r.projection = project_data(f, locator, points);  // paper §3.1: foot points, d_k, closest triangles
  std::vector<Vec3> normals;
  std::vector<PrincipalCurvatures> curvatures;
  vertex_geometry(f, base, normals, curvatures);
  const auto filter = displacement_filters().create(options.filter, "displacement filter");
  r.scale = scale ? *scale : filter->measure(points);
  Stopwatch part;
  const double edge = locator.mean_edge_length();
  const FilterInput in{base, r.projection, points, normals, locator.vertex_neighbours(), edge,
                       options.sigma_factor * edge, r.scale, *sparse_gaps_from_name(options.gaps)};
  const VertexFilters filters = filter->build(in);
  const double filter_seconds = part.seconds();
  std::vector<double> d(base.vertices.size(), 0.0);
  add_filtered(filters.taps, r.projection.displacements, d);
  const ResidualPassReport passes =
      apply_residual_passes(base, r.projection, points, normals, filters, in.paper_width, options.residual_passes,
                            options.fine_residual_passes, r.scale.noise_sigma > 0, d);
  nlohmann::json s = {{"method", options.filter}, {"points", points.size()}, {"vertices", base.vertices.size()},
                      {"faces", base.faces.size()}};
  std::vector<char> known = filters.known;
  r.hole_vertices = hole_vertices(locator, filters, options.rim_offset, known, d, s);
  describe_filter(filters, known, r.scale, scale == nullptr, s);
  // Holes: the harmonic fill, so the displaced surface continues across without a step at the rim.
  HoleTreatmentReport holes;
  if (!r.hole_vertices.empty()) holes.fill = harmonic_fill(locator.vertex_neighbours(), known, d);
  r.mesh = base;  // Eq. 2: v <- v + d(v) n(v)
  r.mesh.normals = normals;
  for (std::size_t v = 0; v < base.vertices.size(); ++v) r.mesh.vertices[v] = base.vertices[v] + d[v] * normals[v];
  hole_treatments().create(options.hole_fill, "hole treatment")
      ->fair(base, normals, locator.vertex_neighbours(), r.hole_vertices, d, r.mesh, holes);
  r.vertex_displacement = d;
  FlipCheck flips = check_flips(base, r.mesh.vertices, d, curvatures, locator,
                                holes.fairing.vertices > 0 ? r.hole_vertices : std::vector<int>{});
  r.at_risk_vertices = std::move(flips.at_risk_vertices);
  r.flipped_faces = std::move(flips.flipped_faces);
  r.flipped_vertices = std::move(flips.flipped_vertices);
  r.needs_refinement = !r.flipped_faces.empty();
  s["projection"] = r.projection.summary();
  s["residual_passes"] = passes.passes;
  s["fine_residual_passes"] = passes.fine_passes;
  s["fine_residual_vertices"] = passes.fine_vertices;
  if (r.scale.noise_sigma > 0) s["residual_rms"] = passes.residual_rms;
  s.update(holes.summary());
  describe_result(r, flips.faces_tested, s);
  s["noise_seconds"] = scale ? 0.0 : r.scale.seconds;
  s["filter_seconds"] = filter_seconds;
  s["seconds"] = timer.seconds();  // the D-Map time of Table 1, without the error report below
  s["errors_before"] = onering_errors(locator, points);
  s["errors_after"] = onering_errors(MeshLocator(r.mesh), points);
  r.summary = std::move(s);
  return r;
}

void register_displacers() {
  displacement_filters();
  hole_treatments();
}

}  // namespace dtsl
