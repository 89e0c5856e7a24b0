// Shared pieces of the level-set evolution tests: small point sets with known surfaces (built through
// the framework's datasets where a sampler option matters, e.g. the torus's density_ratio), fast test
// options (max_depth 4-5, small point counts: the suite runs on a loaded 2-core machine), zero-set
// extraction with the marching_cubes polygonizer and exact Newton distances of the data to f = 0.
#pragma once

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "algorithms/evolution/evolution.hpp"
#include "algorithms/evolution/initial_level_set.hpp"
#include "algorithms/evolution/least_squares_rows.hpp"
#include "algorithms/evolution/zero_set.hpp"
#include "algorithms/polygonize/marching_cubes.hpp"
#include "algorithms/polygonize/newton_projection.hpp"
#include "framework/datasets/dataset.hpp"
#include "framework/metrics/metrics.hpp"
#include "tests/tspline/point_sets.hpp"

namespace dtsl::test {

/// Points of a dataset spec (YAML, docs/design.md §7 syntax), in the [-1,1]^3 frame.
inline std::vector<Vec3> dataset_points(const std::string& yaml, std::uint64_t seed = 1) {
  register_dataset_plugins();
  DatasetSpec spec = parse_dataset(YAML::Load(yaml), "test");
  return build_dataset(spec, seed).points.points;
}

/// A unit-radius-ish sphere (radius 0.8 about the origin), `n` uniform points.
inline std::vector<Vec3> sphere_data(std::size_t n = 1500) { return sphere_points(n, 0.8, Vec3::Zero(), 3); }

/// The torus (R = 1, r = 0.4 before normalisation) with density growing 6x along x: the level set must
/// open its hole by itself (genus 0 -> 1).
inline const std::vector<Vec3>& torus_data() {
  static const std::vector<Vec3> p = dataset_points(
      "{name: torus, shape: {type: torus, R: 1.0, r: 0.4}, "
      "sampler: {type: area, count: 2500, density_ratio: 6, density_axis: x}}");
  return p;
}

/// Two separate spheres along x.
inline const std::vector<Vec3>& two_spheres_data() {
  static const std::vector<Vec3> p =
      dataset_points("{name: two, shape: {type: two_spheres, gap: 2.0}, sampler: {type: area, count: 2000}}");
  return p;
}

/// Options for the tests: the defaults except a shallow T-mesh (fast) and the given plugins.
inline EvolutionOptions test_options(const std::string& velocity, const std::string& solver, int max_depth = 4) {
  EvolutionOptions o;
  o.velocity = velocity;
  o.solver = solver;
  o.tmesh.max_depth = max_depth;
  o.tmesh.points_per_cell = 16;
  o.fine.levels = 0;  // the evolution on one T-mesh; coarse_to_fine_test.cpp tests the rounds
  return o;
}

/// The least-squares system of one evolution step from the initial surface (velocity rows with a
/// prescribed inward speed, the distance-field band, the Tikhonov rows): a realistic system for
/// comparing solvers.
inline LeastSquaresSystem step_system(const std::vector<Vec3>& points, const EvolutionOptions& o) {
  auto basis = std::make_shared<TSplineBasis>(build_octree(points, o.tmesh));
  const TSpline f = initial_level_set(basis, points, o.initial_radius_factor, o.initial_box_margin);
  ZeroSetSampling sampling;
  const ZeroSetSamples s = sample_zero_set(f, basis->octree(), sampling);
  LeastSquaresBuilder rows(*basis);
  std::vector<Vec3> x;
  std::vector<double> target;
  for (const SurfacePoint& p : s.surface) {
    x.push_back(p.position);
    target.push_back((0.1 + 0.05 * std::sin(7 * p.position.x())) * p.gradient.norm());
  }
  rows.add_value_rows(x, target, 1.0);
  std::vector<Vec3> direction;
  std::vector<double> rhs;
  for (std::size_t m = 0; m < s.band.size(); ++m) {
    direction.push_back(2.0 * 0.3 * s.band_gradient[m]);
    rhs.push_back(1.0 - s.band_gradient[m].squaredNorm());
  }
  rows.add_gradient_rows(s.band, direction, rhs, o.w_distance);
  return rows.finish(o.w_smooth);
}

/// The zero set as a triangle mesh (marching tetrahedra on a grid over the data's box), for genus and
/// component counts.
inline TriangleMesh zero_set_mesh(const ImplicitFunction& f, const std::vector<Vec3>& data, double step = 0.04,
                                  const std::string& region = "data") {
  MarchingCubesOptions o;
  o.step = step;
  o.region = region;
  o.margin = 0.2;
  o.drop_dataless_components = false;  // every component counts: a stray one is a failure to see
  return marching_cubes(f, data, o).mesh;
}

struct NewtonDistances {
  double mean = 0.0, max = 0.0;
  int failed = 0;  ///< points whose Newton projection did not converge
};

/// Exact distances |p - q| of the data to their Newton foot points q on f = 0.
inline NewtonDistances newton_distances(const ImplicitFunction& f, const std::vector<Vec3>& points) {
  NewtonOptions o;
  o.tolerance = 1e-9;
  o.max_iterations = 100;
  o.max_step = 0.05;
  NewtonDistances d;
  const auto projections = newton_project_all(f, points, o);
  int counted = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!projections[k].converged()) {
      ++d.failed;
      continue;
    }
    const double dist = (projections[k].point - points[k]).norm();
    d.mean += dist;
    d.max = std::max(d.max, dist);
    ++counted;
  }
  if (counted > 0) d.mean /= counted;
  return d;
}

/// Range of |grad f| over the zero set, sampled at the extracted mesh's vertices.
inline std::pair<double, double> gradient_range_on_zero_set(const ImplicitFunction& f, const TriangleMesh& mesh) {
  double lo = 1e300, hi = 0.0;
  for (const Vec3& v : mesh.vertices) {
    const double g = f.gradient(v).norm();
    lo = std::min(lo, g);
    hi = std::max(hi, g);
  }
  return {lo, hi};
}

}  // namespace dtsl::test
