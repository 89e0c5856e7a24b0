// How noisy are the data? (ours; the paper assumes the user picks the filter.) Every sampled point's k
// nearest neighbours get a quadric height field z = c0 + c1 u + c2 w + c3 u^2 + c4 uw + c5 w^2 in their
// PCA frame (a degree-2 jet, as in CGAL's jet fitting); the RMS of its residuals, with k - 6 degrees of
// freedom, measures the noise along the normal plus whatever shape a quadric cannot follow at that
// scale. The two separate by how they grow with k: independent noise reads the same at every k, while
// the shape's third-order remainder grows like r^3 ~ k^(3/2), its square like k^3. So the fit is made
// at two neighbourhood sizes and the quantile RMS extrapolated to zero size, s^2 = sigma^2 + c k^3
// (Richardson's extrapolation). Without it a clean but sparse scan of a detailed shape reads as noisy
// as a noisy dense one (docs/design.md §8).
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "framework/config/options.hpp"
#include "framework/core/types.hpp"

namespace dtsl {

struct NoiseEstimateOptions final : Options {
  /// Neighbours per fit at the larger and the smaller scale (the point itself included); at least 10
  /// so that the 6-parameter fit has residual degrees of freedom to measure.
  int neighbours = 24;
  int small_neighbours = 12;
  /// At most this many points are fitted (evenly strided through the input, so the answer does not
  /// depend on the thread count); the median of a few thousand is stable (docs/design.md §8).
  int max_samples = 4000;
  /// The estimate is this quantile of the points' residual RMS, divided by the same quantile of the
  /// RMS pure Gaussian noise would give (chi with k - 6 degrees of freedom), so it reads sigma on pure
  /// noise whatever the quantile. Below the median it is less swayed by neighbourhoods whose shape a
  /// quadric cannot follow (fine relief, creases), which read as extra noise.
  double quantile = 0.5;

  void visit(FieldVisitor& v) override;
  void check() const override;
};

struct NoiseEstimate {
  double sigma = 0.0;        ///< the noise: the residual RMS extrapolated to a zero-size neighbourhood
  double rms_small = 0.0;    ///< the points' residual RMS at `quantile`, chi-corrected, with small_neighbours
  double rms_large = 0.0;    ///< the same with `neighbours`
  double spacing = 0.0;      ///< median distance to the nearest neighbour (frame units)
  int fitted_points = 0;     ///< neighbourhoods fitted (degenerate ones, e.g. collinear, are skipped)
  nlohmann::json summary() const;
};

/// Throws AlgorithmError when there are fewer points than `neighbours` or a point is not finite;
/// ConfigError when small_neighbours is not below neighbours.
NoiseEstimate estimate_noise(const std::vector<Vec3>& points, const NoiseEstimateOptions& options = {});

}  // namespace dtsl
