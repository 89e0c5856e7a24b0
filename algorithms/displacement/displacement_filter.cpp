// The registry of displacement filters and its two entries (paper §3.2 and ours).
#include "algorithms/displacement/displacement_filter.hpp"

#include "framework/core/timer.hpp"

namespace dtsl {

namespace {

// An estimated noise below this x the data's median spacing is taken as none: the estimate cannot tell
// such a small figure from unresolved relief. Measured with bench/noise_estimate: clean data read
// 0-1.4 % (the 6k bunny 0.25e-3 at spacing 17e-3, the torus 0.6 %), the torus with noise sigma 1e-3
// 5.2 %, the noisy 25k models 23-25 %.
constexpr double kNoiseFloor = 0.03;
// Noisy data: successive widths differ by sqrt(2) (the geometric grid of LPA-ICI), up to 4 mean edge
// lengths, eight times the paper's width.
constexpr double kWidthRatio = 1.41421356237;
constexpr double kWidestWidthEdges = 4.0;

// The paper's filter: one Gaussian width, a mean.
class GaussianFilter final : public DisplacementFilter {
 public:
  DataScale measure(const std::vector<Vec3>&) const override { return {}; }
  VertexFilters build(const FilterInput& in) const override {
    return build_vertex_filters(in, FilterLadder{{in.paper_width}, false, 0.0});
  }
};

// Ours: the filter follows the data's noise and spacing (the header's `adaptive`).
class AdaptiveFilter final : public DisplacementFilter {
 public:
  DataScale measure(const std::vector<Vec3>& points) const override {
    DataScale scale;
    const NoiseEstimateOptions options;
    if (points.size() < static_cast<std::size_t>(options.neighbours)) return scale;  // too few: the paper's filter
    Stopwatch timer;
    scale.estimate = estimate_noise(points, options);
    const NoiseEstimate& e = *scale.estimate;
    scale.noise_sigma = e.sigma >= kNoiseFloor * e.spacing ? e.sigma : 0.0;
    if (scale.noise_sigma == 0) scale.spacing = e.spacing;  // noise-free: the base width follows the spacing
    scale.seconds = timer.seconds();
    return scale;
  }

  VertexFilters build(const FilterInput& in) const override {
    FilterLadder ladder;
    const DataScale& s = in.scale;
    // Noise-free data sparser than the mesh: at the paper's width (support 1.5 edges) a vertex sees a
    // few feet where the spacing nears 1.5 edges, and d jumps from vertex to vertex wherever the base is
    // tilted against the data; a plane fitted over the spacing does not. configs/ablation_sparse_filter.yaml:
    // a width of 1 x the spacing lowered chamfer on all four noise-free models (fandisk cut 8.51 ->
    // 7.73e-3, holed bunny 1.99 -> 1.86, block 2.26 -> 2.07, torus 0.60 -> 0.58), 0.75 x less so.
    ladder.base_fits = s.spacing > 0 && s.noise_sigma == 0;
    double width = in.paper_width;
    if (ladder.base_fits) width = std::max(width, s.spacing);
    ladder.widths = {width};
    ladder.noise_sigma = s.noise_sigma;
    // The gaps between sparse data (the header; docs/design.md §8, "Gaps between sparse data").
    if (ladder.base_fits && in.gaps != SparseGaps::fit) ladder.support_width = in.paper_width;
    if (s.noise_sigma > 0)
      while (ladder.widths.back() * kWidthRatio <= kWidestWidthEdges * in.mean_edge * (1 + 1e-9))
        ladder.widths.push_back(ladder.widths.back() * kWidthRatio);
    return build_vertex_filters(in, ladder);
  }
};

}  // namespace

Registry<DisplacementFilter>& displacement_filters() {
  static Registry<DisplacementFilter> registry("displacement filter");
  static const bool registered = [] {
    registry.add("gaussian", "paper §3.2: the Gaussian mean of the d_k, sigma_factor x the mean edge length wide",
                 [] { return std::make_unique<GaussianFilter>(); });
    registry.add("adaptive",
                 "ours: noisy data, a width per vertex by ICI fitting a plane; noise-free data, a plane fitted over "
                 "the data's spacing (the paper's narrow mean follows in the fine residual passes)",
                 [] { return std::make_unique<AdaptiveFilter>(); });
    return true;
  }();
  (void)registered;
  return registry;
}

std::optional<SparseGaps> sparse_gaps_from_name(const std::string& name) {
  for (std::size_t i = 0; i < std::size(kSparseGapsNames); ++i)
    if (name == kSparseGapsNames[i]) return static_cast<SparseGaps>(i);
  return std::nullopt;
}

}  // namespace dtsl
