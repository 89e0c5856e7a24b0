// Result against ground truth (docs/design.md §5): area-uniform samples on both surfaces, exact distances
// from each sample set to the other surface, and the scores built from them.
#include <cmath>
#include <random>
#include <string>

#include "framework/core/error.hpp"
#include "framework/core/sampling.hpp"
#include "framework/metrics/metrics.hpp"

namespace dtsl {

namespace {

// The statistics of one direction: samples on one surface measured against the other.
struct Directed {
  double mean = 0.0, max = 0.0, normal = 0.0, within_tau = 0.0;
};

Directed measure(const std::vector<SurfaceSample>& samples, const MeshDistance& distance,
                 const TriangleMesh& target, double tau) {
  Directed d;
  double sum = 0.0, normal_sum = 0.0;
  std::size_t within = 0;
  std::vector<Vec3> points(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) points[i] = samples[i].point;
  const std::vector<MeshDistance::Hit> hits = distance.closest_all(points);
  for (std::size_t i = 0; i < samples.size(); ++i) {  // in sample order: the sums are reproducible
    const SurfaceSample& s = samples[i];
    const MeshDistance::Hit& hit = hits[i];
    sum += hit.distance;
    if (hit.distance > d.max) d.max = hit.distance;
    if (hit.distance <= tau) ++within;
    // |n.n'|: the orientation of either mesh must not matter, only the agreement of the tangent planes.
    normal_sum += std::abs(s.normal.dot(face_normal(target, hit.face)));
  }
  const double n = static_cast<double>(samples.size());
  d.mean = sum / n;
  d.normal = normal_sum / n;
  d.within_tau = static_cast<double>(within) / n;
  return d;
}

std::vector<SurfaceSample> samples_on(const TriangleMesh& mesh, std::size_t count, std::uint64_t seed,
                                      std::uint32_t stream, const char* what) {
  // One stream per surface, both fixed by the seed, so neither sample set depends on the other mesh.
  std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32), stream};
  std::mt19937_64 rng(seq);
  try {
    return sample_surface(mesh, count, rng);
  } catch (const AlgorithmError& e) {
    throw AlgorithmError(std::string("comparing surfaces: ") + what + " mesh: " + e.what());
  }
}

// C++17 guaranteed elision lets the non-movable tree be returned.
MeshDistance distance_to(const TriangleMesh& mesh, const char* what) {
  try {
    return MeshDistance(mesh);
  } catch (const AlgorithmError& e) {
    throw AlgorithmError(std::string("comparing surfaces: ") + what + " " + e.what());
  }
}

// Box of the vertices the faces use: stray unreferenced vertices must not change tau.
double referenced_diagonal(const TriangleMesh& mesh) {
  BoundingBox box;
  for (const Face& f : mesh.faces)
    for (int i : f) box.extend(mesh.vertices[i]);
  return box.diagonal();
}

}  // namespace

SurfaceMetrics compare_surfaces(const TriangleMesh& result, const TriangleMesh& truth, std::size_t samples,
                                double tau_ratio, std::uint64_t seed) {
  if (samples == 0) throw AlgorithmError("comparing surfaces: samples must be positive, got 0");
  if (!(std::isfinite(tau_ratio) && tau_ratio >= 0.0))
    throw AlgorithmError("comparing surfaces: tau_ratio must be finite and not negative, got " +
                         std::to_string(tau_ratio));
  // The trees come first: they validate the meshes (faces, indices, finite vertices) before the
  // sampler reads them.
  const MeshDistance to_result = distance_to(result, "result");
  const MeshDistance to_truth = distance_to(truth, "truth");

  SurfaceMetrics m;
  m.tau = tau_ratio * referenced_diagonal(truth);
  const std::vector<SurfaceSample> on_result = samples_on(result, samples, seed, 0, "result");
  const std::vector<SurfaceSample> on_truth = samples_on(truth, samples, seed, 1, "truth");
  const Directed r_to_g = measure(on_result, to_truth, truth, m.tau);
  const Directed g_to_r = measure(on_truth, to_result, result, m.tau);

  m.accuracy = r_to_g.mean;
  m.completeness = g_to_r.mean;
  m.chamfer = 0.5 * (m.accuracy + m.completeness);
  m.hausdorff = std::max(r_to_g.max, g_to_r.max);
  m.normal_consistency = 0.5 * (r_to_g.normal + g_to_r.normal);
  m.precision = r_to_g.within_tau;
  m.recall = g_to_r.within_tau;
  m.fscore = m.precision + m.recall > 0.0 ? 2.0 * m.precision * m.recall / (m.precision + m.recall) : 0.0;
  return m;
}

}  // namespace dtsl
