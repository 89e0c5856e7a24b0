#include "algorithms/displacement/noise_estimate.hpp"

#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/property_map.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>

#include "framework/core/error.hpp"

namespace dtsl {

void NoiseEstimateOptions::visit(FieldVisitor& v) {
  v.field("neighbours", neighbours, "nearest neighbours per quadric fit at the larger scale (the point included)");
  v.field("small_neighbours", small_neighbours, "nearest neighbours per quadric fit at the smaller scale");
  v.field("max_samples", max_samples, "at most this many points are fitted (evenly strided)");
  v.field("quantile", quantile,
          "quantile of the points' residual RMS taken (chi-corrected: pure noise reads sigma at any quantile)");
}

void NoiseEstimateOptions::check() const {
  check_range("neighbours", neighbours, 11, 1000);
  check_range("small_neighbours", small_neighbours, 10, 1000);
  require(small_neighbours < neighbours, "small_neighbours",
          "must be below neighbours (" + std::to_string(neighbours) + "), got " + std::to_string(small_neighbours));
  check_range("max_samples", max_samples, 1, 100000000);
  check_range("quantile", quantile, 0.05, 0.95);
}

nlohmann::json NoiseEstimate::summary() const {
  return {{"sigma", sigma}, {"rms_small", rms_small}, {"rms_large", rms_large}, {"spacing", spacing},
          {"fitted_points", fitted_points}};
}

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using PointMap = CGAL::Pointer_property_map<Point>::type;
using Traits = CGAL::Search_traits_adapter<std::size_t, PointMap, CGAL::Search_traits_3<Kernel>>;
using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;
using Tree = Search::Tree;

double quantile_of(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const auto at = v.begin() + static_cast<long>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), at, v.end());
  return *at;
}

// The q-quantile of sqrt(chi^2_nu / nu): Wilson-Hilferty's cube-root normal approximation (error below
// 0.5 % for nu >= 4), with the normal quantile found by bisection on erf.
double chi_rms_quantile(double q, int nu) {
  double lo = -10.0, hi = 10.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(-mid / std::sqrt(2.0)) < q ? lo : hi) = mid;
  }
  const double z = 0.5 * (lo + hi), a = 2.0 / (9.0 * nu);
  return std::pow(1.0 - a + z * std::sqrt(a), 1.5);
}

// Residual RMS of the quadric height field over `nb` (k points), -1 when the neighbourhood is degenerate.
double quadric_residual_rms(const std::vector<Vec3>& nb) {
  const int k = static_cast<int>(nb.size());
  Vec3 centre = Vec3::Zero();
  for (const Vec3& p : nb) centre += p;
  centre /= k;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& p : nb) cov += (p - centre) * (p - centre).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  if (eig.info() != Eigen::Success || !(eig.eigenvalues()(1) > 0)) return -1.0;
  // Smallest eigenvector: the normal; the other two span the tangent plane. Scale u, w by the
  // neighbourhood's size so the normal matrix is well conditioned whatever the spacing.
  const Vec3 n = eig.eigenvectors().col(0), t1 = eig.eigenvectors().col(2), t2 = eig.eigenvectors().col(1);
  const double scale = std::sqrt(eig.eigenvalues()(2) / k);
  Eigen::MatrixXd A(k, 6);
  Eigen::VectorXd z(k);
  for (int i = 0; i < k; ++i) {
    const Vec3 d = nb[i] - centre;
    const double u = d.dot(t1) / scale, w = d.dot(t2) / scale;
    A.row(i) << 1.0, u, w, u * u, u * w, w * w;
    z(i) = d.dot(n);
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  if (qr.rank() < 6) return -1.0;  // e.g. all neighbours on one line of the tangent plane
  const Eigen::VectorXd r = A * qr.solve(z) - z;
  return std::sqrt(r.squaredNorm() / (k - 6));
}

}  // namespace

NoiseEstimate estimate_noise(const std::vector<Vec3>& points, const NoiseEstimateOptions& options) {
  options.check();
  const std::size_t n = points.size();
  if (n < static_cast<std::size_t>(options.neighbours))
    throw AlgorithmError("noise estimate: " + std::to_string(n) + " points, fewer than the " +
                         std::to_string(options.neighbours) + " neighbours a fit needs");
  std::vector<Point> cgal_points;
  cgal_points.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!points[i].allFinite()) throw AlgorithmError("noise estimate: point " + std::to_string(i) + " is not finite");
    cgal_points.emplace_back(points[i].x(), points[i].y(), points[i].z());
  }
  std::vector<std::size_t> ids(n);
  for (std::size_t i = 0; i < n; ++i) ids[i] = i;
  const PointMap map = CGAL::make_property_map(cgal_points);
  Tree tree(ids.begin(), ids.end(), Tree::Splitter(), Traits(map));
  tree.build();  // before the parallel loop: the lazy build is not thread-safe

  const std::size_t samples = std::min<std::size_t>(n, static_cast<std::size_t>(options.max_samples));
  const int k_small = options.small_neighbours, k_large = options.neighbours;
  std::vector<double> rms_small(samples, -1.0), rms_large(samples, -1.0), nearest(samples, -1.0);
#pragma omp parallel for schedule(dynamic, 64)
  for (long s = 0; s < static_cast<long>(samples); ++s) {
    const std::size_t i = static_cast<std::size_t>(s) * n / samples;
    Search search(tree, cgal_points[i], static_cast<unsigned>(k_large), 0.0, true, Search::Distance(map));
    std::vector<Vec3> nb;  // nearest first
    nb.reserve(k_large);
    for (const auto& hit : search) {
      nb.push_back(points[hit.first]);
      // The nearest other point: the first hit is the point itself; duplicates (distance 0) are skipped,
      // or a cloud with repeated points would read a spacing of 0 and its noise floor would vanish.
      if (nearest[s] < 0 && hit.second > 0) nearest[s] = std::sqrt(hit.second);
    }
    rms_large[s] = quadric_residual_rms(nb);
    nb.resize(std::min<std::size_t>(nb.size(), k_small));
    rms_small[s] = quadric_residual_rms(nb);
  }
  const auto at_quantile = [&](const std::vector<double>& rms, int k) {
    std::vector<double> good;
    for (double r : rms)
      if (r >= 0) good.push_back(r);
    return std::make_pair(good.empty() ? 0.0 : quantile_of(good, options.quantile) / chi_rms_quantile(options.quantile, k - 6),
                          static_cast<int>(good.size()));
  };
  NoiseEstimate e;
  int fitted_small = 0;
  std::tie(e.rms_small, fitted_small) = at_quantile(rms_small, k_small);
  std::tie(e.rms_large, e.fitted_points) = at_quantile(rms_large, k_large);
  e.fitted_points = std::min(e.fitted_points, fitted_small);
  // s_k^2 = sigma^2 + c k^3 at both sizes; sigma^2 >= 0, and never above the smaller scale's reading.
  const double a = std::pow(static_cast<double>(k_small), 3), b = std::pow(static_cast<double>(k_large), 3);
  const double s2 = (b * e.rms_small * e.rms_small - a * e.rms_large * e.rms_large) / (b - a);
  e.sigma = std::sqrt(std::clamp(s2, 0.0, e.rms_small * e.rms_small));
  std::vector<double> gaps;
  for (double g : nearest)
    if (g >= 0) gaps.push_back(g);
  e.spacing = quantile_of(gaps, 0.5);
  return e;
}

}  // namespace dtsl
