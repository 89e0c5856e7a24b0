#include "algorithms/evolution/zero_set.hpp"

#include <algorithm>
#include <cmath>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace dtsl {

namespace {

/// Newton projection from a cell centre onto f = 0 (paper §3.1 step 3.2), each step capped at
/// `max_step`; true if |f| / |grad f| fell below `tolerance`.
bool project(const ImplicitFunction& f, Vec3& x, double max_step, double tolerance, int iterations) {
  Vec3 g;
  for (int it = 0; it <= iterations; ++it) {
    const double v = f.evaluate(x, &g);
    const double g2 = g.squaredNorm();
    if (!(g2 > 0.0) || !std::isfinite(v)) return false;
    const double length = std::abs(v) / std::sqrt(g2);
    if (length < tolerance) return true;
    if (it == iterations) return false;
    Vec3 step = (v / g2) * g;
    if (length > max_step) step *= max_step / length;
    x -= step;
  }
  return false;
}

}  // namespace

ZeroSetSamples sample_zero_set(const ImplicitFunction& f, const Octree& tmesh, const ZeroSetSampling& options) {
  const int s = std::max(1, options.subdivision);
  const int leaves = tmesh.leaf_count();
  const BoundingBox domain = tmesh.domain();
  int threads = 1;
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif
  std::vector<ZeroSetSamples> parts(threads);
#pragma omp parallel num_threads(threads)
  {
    int t = 0;
#ifdef _OPENMP
    t = omp_get_thread_num();
#endif
    ZeroSetSamples& out = parts[t];
    const int begin = int(long(leaves) * t / threads), end = int(long(leaves) * (t + 1) / threads);
    const int b = std::max(1, options.band_subdivision);
    for (int l = begin; l < end; ++l) {
      const BoundingBox box = tmesh.leaf_box(l);
      const double side = tmesh.leaf_side(l);
      // Band candidates.
      const double hb = side / b;
      for (int k = 0; k < b * b * b; ++k) {
        const Vec3 centre = box.min + hb * Vec3(k % b + 0.5, (k / b) % b + 0.5, k / (b * b) + 0.5);
        Vec3 g;
        const double v = f.evaluate(centre, &g);
        const double gn = g.norm();
        if (!(gn > 0.0) || std::abs(v) >= options.band_width * side * gn) continue;
        out.band.push_back(centre);
        out.band_gradient.push_back(g);
        out.band_cell_size.push_back(side);
        out.band_site.push_back(l * b * b * b + k);
      }
      // Zero-set candidates.
      const double h = side / s;
      for (int k = 0; k < s * s * s; ++k) {
        const Vec3 centre = box.min + h * Vec3(k % s + 0.5, (k / s) % s + 0.5, k / (s * s) + 0.5);
        Vec3 g;
        const double v = f.evaluate(centre, &g);
        const double gn = g.norm();
        if (!(gn > 0.0)) continue;
        // The surface can cross the sub-cell only if it passes within half its diagonal of the
        // centre (to first order; 1.5x for the curvature of f).
        if (std::abs(v) > 1.5 * 0.8660254037844386 * h * gn) continue;
        Vec3 x = centre;
        if (!project(f, x, h, 1e-7 * h, options.newton_iterations)) continue;
        if (((x - centre).cwiseAbs().array() > 0.5 * h).any()) continue;  // another cell's point
        if (((x - domain.min).array() < 0.0).any() || ((x - domain.max).array() > 0.0).any()) continue;
        SurfacePoint p;
        p.position = x;
        p.hessian.setZero();
        f.evaluate(x, &p.gradient, options.hessians ? &p.hessian : nullptr);
        p.cell_size = side;
        p.leaf = l;
        out.surface.push_back(p);
        out.band.push_back(x);
        out.band_gradient.push_back(p.gradient);
        out.band_cell_size.push_back(side);
        out.band_site.push_back(-1);
      }
    }
  }
  ZeroSetSamples all = std::move(parts[0]);
  for (int t = 1; t < threads; ++t) {
    all.surface.insert(all.surface.end(), parts[t].surface.begin(), parts[t].surface.end());
    all.band.insert(all.band.end(), parts[t].band.begin(), parts[t].band.end());
    all.band_gradient.insert(all.band_gradient.end(), parts[t].band_gradient.begin(), parts[t].band_gradient.end());
    all.band_cell_size.insert(all.band_cell_size.end(), parts[t].band_cell_size.begin(), parts[t].band_cell_size.end());
    all.band_site.insert(all.band_site.end(), parts[t].band_site.begin(), parts[t].band_site.end());
  }
  return all;
}

}  // namespace dtsl
