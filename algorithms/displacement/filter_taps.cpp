// Every vertex's filter over a ladder of widths: the base width's taps, then on noisy data the widest
// width the intersection of confidence intervals (ICI; Katkovnik, "A new method for varying adaptive
// bandwidth selection", IEEE TSP 1999) admits, median-smoothed over the one-ring.
#include <algorithm>
#include <cmath>

#include "algorithms/displacement/displacement_filter.hpp"
#include "algorithms/displacement/local_regression.hpp"
#include "algorithms/displacement/vertex_grid.hpp"

namespace dtsl {

namespace {

// ICI's threshold: a vertex widens while the intervals [d_j - t s_j, d_j + t s_j] still share a point.
// configs/ablation_noise.yaml: 1.5 and 3 raised chamfer on all three noisy models (armadillo 1.34 ->
// 1.45 / 1.80e-3, diplodocus 0.96 -> 1.01 / 1.19, noisy torus 1.79 -> 1.84 / 2.15).
constexpr double kIciThreshold = 1.0;
// One-ring median passes over ICI's chosen widths: its choices jump between neighbours, and a patchwork
// of widths is a patchwork of biases. configs/ablation_noise.yaml: unsmoothed, chamfer 1.34 -> 1.44e-3
// (armadillo), 0.96 -> 1.18 (diplodocus), 1.79 -> 2.14 (noisy torus).
constexpr int kIciSmoothingPasses = 4;
// The degree of the local polynomial the fitting widths fit: linear is unbiased where d varies linearly
// (a tilted base surface). configs/ablation_noise.yaml: degree 0 and 2 both raised chamfer on the
// armadillo (1.34 -> 1.42 / 1.47e-3) and the diplodocus (0.96 -> 1.08 / 1.05).
constexpr int kRegressionDegree = 1;

class TapBuilder {
 public:
  TapBuilder(const FilterInput& in, const FilterLadder& ladder, VertexFilters& out)
      : in_(in), ladder_(ladder), out_(out), feet_(*out.feet) {}

  // Width j's taps for v, with polynomial weights where the width fits; false where they fail the hole
  // test. The base width also measures the taps' one-sidedness (the hole rim test).
  bool taps_at(long v, const FootReach& reach, std::size_t j, FilterTaps& taps, int* degree) const {
    const double width = ladder_.widths[j];
    if (!feet_.gaussian_taps(reach, width, taps)) return false;
    if (j == 0) out_.one_sidedness[v] = feet_.one_sidedness(v, taps, width);
    *degree = j > 0 || ladder_.base_fits
                  ? local_regression_weights(taps, in_.projection.foot_points, in_.base.vertices[v], in_.normals[v],
                                             width, kRegressionDegree)
                  : 0;
    return true;
  }

  // The support test at ladder_.support_width, narrower than the base width (whose support holds the
  // reach): data within it, or v is a hole.
  bool supported(const FootReach& reach) const {
    return !(ladder_.support_width > 0 && ladder_.support_width < ladder_.widths.front()) ||
           feet_.supported(reach, ladder_.support_width);
  }

  // The ICI estimate of taps: the filtered d and its interval's half-width.
  double estimate(const FilterTaps& taps, double* deviation) const {
    double e = 0.0, l2 = 0.0;
    for (const auto& [k, l] : taps) e += l * in_.projection.displacements[k], l2 += l * l;
    *deviation = kIciThreshold * ladder_.noise_sigma * std::sqrt(l2);
    return e;
  }

  // v's base taps, then wider ones while the confidence intervals of the estimates so far intersect.
  void build(long v, std::vector<int>& width_index, std::vector<char>& unsupported) const {
    const std::vector<double>& widths = ladder_.widths;
    FilterTaps& taps = out_.taps[v];
    FootReach reach;
    feet_.gather(v, reach, feet_.near());
    std::size_t reached = feet_.near();  // reach holds the feet of widths 0..reached
    int degree = 0;
    if (!taps_at(v, reach, 0, taps, &degree)) {
      taps.clear();
      return;
    }
    if (!supported(reach)) unsupported[v] = 1;
    out_.known[v] = 1;
    out_.degree[v] = degree;
    double dev = 0.0, e = estimate(taps, &dev);
    double lower = e - dev, upper = e + dev;
    FilterTaps wider;
    for (std::size_t j = 1; j < widths.size(); ++j) {
      if (j > reached) feet_.gather(v, reach, reached = widths.size() - 1);
      if (!taps_at(v, reach, j, wider, &degree)) break;
      e = estimate(wider, &dev);
      lower = std::max(lower, e - dev), upper = std::min(upper, e + dev);
      if (lower > upper) break;
      taps.swap(wider);
      width_index[v] = static_cast<int>(j);
      out_.degree[v] = degree;
      out_.width[v] = widths[j];
    }
  }

  // v's taps at the smoothed width (or the next narrower one whose taps pass the hole test: thinned feet
  // can weigh too little), from all the feet again once it is one of the near() widths.
  void rebuild(long v, int index) const {
    FootReach reach;
    FilterTaps taps;
    feet_.gather(v, reach, static_cast<std::size_t>(index));
    for (int j = index; j >= 0; --j) {
      if (static_cast<std::size_t>(j) == feet_.near() && static_cast<std::size_t>(index) > feet_.near())
        feet_.gather(v, reach, feet_.near());
      int degree = 0;
      if (taps_at(v, reach, static_cast<std::size_t>(j), taps, &degree)) {
        out_.taps[v].swap(taps);
        out_.degree[v] = degree;
        out_.width[v] = ladder_.widths[j];
        return;
      }
    }
  }

 private:
  const FilterInput& in_;
  const FilterLadder& ladder_;
  VertexFilters& out_;
  const FootNeighbourhoods& feet_;
};

// Each known vertex's width index becomes the median of its one-ring's, kIciSmoothingPasses times.
std::vector<int> smoothed_widths(const std::vector<std::vector<int>>& neighbours, const std::vector<char>& known,
                                 std::vector<int> width_index) {
  const long nv = static_cast<long>(width_index.size());
  for (int pass = 0; pass < kIciSmoothingPasses; ++pass) {
    std::vector<int> next = width_index;
#pragma omp parallel for schedule(static)
    for (long v = 0; v < nv; ++v) {
      if (!known[v]) continue;
      std::vector<int> ring{width_index[v]};
      for (int u : neighbours[v])
        if (known[u]) ring.push_back(width_index[u]);
      std::nth_element(ring.begin(), ring.begin() + static_cast<long>(ring.size() / 2), ring.end());
      next[v] = ring[ring.size() / 2];
    }
    width_index.swap(next);
  }
  return width_index;
}

// The unsupported vertices (taps, but no data within the support width) become holes, the gaps between
// sparse data, except a hole's margin: those within `reach` (the base filter's reach) of a
// vertex of a hole in the data, joined to one by a path of unsupported or tapless vertices that stays
// within that distance. There the fit carries the data's surface on across the hole's edge, which the
// fairing continues (a plane cut, a scan hole); farther on, the fit would stand in for data that are not
// there. A hole vertex is a tapless one farther from the data than kFilterSupport local spacings of the
// data at the hole's edge (its nearest data point's), never fewer than `reach`: where the data are sparse
// throughout (a CAD model's vertices on its flat faces), a vertex `reach` from them lies in a gap a local
// spacing wide, not at the edge of a hole (docs/design.md §8, "Where a hole's margin starts"). A tapless
// vertex with data nearby starts no margin: there the level set strays from the data and their feet lie
// elsewhere.
void drop_gaps_between_data(const std::vector<Vec3>& points, const std::vector<Vec3>& positions,
                            const std::vector<std::vector<int>>& neighbours, const std::vector<char>& unsupported,
                            double reach, VertexFilters& out) {
  const std::size_t nv = out.known.size();
  std::vector<char> margin(nv, 0);
  std::vector<int> queue;
  std::vector<Vec3> hole_positions;
  if (reach > 0) {
    const PointGrid data(points, reach / 3);
    const double base = reach / kFilterSupport;
    std::vector<int> around_point(points.size(), -1);  // data within `reach` of each point, counted once
    for (std::size_t v = 0; v < nv; ++v) {
      double nearest = 0.0;
      if (out.known[v]) continue;
      const int j = data.nearest(positions[v], &nearest);
      if (j < 0 || nearest <= reach) continue;
      // The local spacing at the hole's edge: the data within `reach` of its nearest point, a half-disk
      // at the edge of a hole, hold about pi reach^2 / (2 s^2) points.
      int& around = around_point[std::size_t(j)];
      if (around < 0) {
        around = 0;
        data.for_each_within(points[std::size_t(j)], reach, [&](int, double) { ++around; });
      }
      const double local = std::max(base, reach * std::sqrt(M_PI / (2.0 * std::max(1, around - 1))));
      if (nearest > kFilterSupport * local) {
        margin[v] = 1;
        queue.push_back(static_cast<int>(v));
        hole_positions.push_back(positions[v]);
      }
    }
  }
  const PointGrid holes(hole_positions, reach > 0 ? reach / 3 : 1.0);
  for (std::size_t q = 0; q < queue.size(); ++q)
    for (int u : neighbours[queue[q]]) {
      if (margin[u] || (out.known[u] && !unsupported[u])) continue;  // marked, or supported data
      double nearest = 0.0;
      if (holes.nearest(positions[u], &nearest) >= 0 && nearest <= reach) margin[u] = 1, queue.push_back(u);
    }
  for (std::size_t v = 0; v < nv; ++v)
    if (unsupported[v] && !margin[v]) out.known[v] = 0, out.taps[v].clear();
}

}  // namespace

VertexFilters build_vertex_filters(const FilterInput& in, const FilterLadder& ladder) {
  const std::size_t nv = in.base.vertices.size();
  VertexFilters out;
  out.taps.resize(nv);
  out.known.assign(nv, 0);
  out.width.assign(nv, ladder.widths.front());
  out.degree.assign(nv, 0);
  out.one_sidedness.assign(nv, 0.0);
  out.base_width = ladder.widths.front();
  out.base_fits = ladder.base_fits;
  out.feet = std::make_unique<FootNeighbourhoods>(in.base, in.projection, in.normals, ladder.widths);
  const TapBuilder builder(in, ladder, out);
  std::vector<int> width_index(nv, 0);
  std::vector<char> unsupported(nv, 0);
#pragma omp parallel for schedule(dynamic, 256)
  for (long v = 0; v < static_cast<long>(nv); ++v) builder.build(v, width_index, unsupported);
  drop_gaps_between_data(in.points, in.base.vertices, in.neighbours, unsupported,
                         kFilterSupport * ladder.widths.front(), out);
  if (!out.feet->widened()) return out;
  const std::vector<int> smoothed = smoothed_widths(in.neighbours, out.known, width_index);
#pragma omp parallel for schedule(dynamic, 256)
  for (long v = 0; v < static_cast<long>(nv); ++v)
    if (out.known[v] && smoothed[v] != width_index[v]) builder.rebuild(v, smoothed[v]);
  return out;
}

}  // namespace dtsl
