// Local polynomial regression of a field sampled at points near a surface vertex (ours; used by the
// displacement filter, DisplacementOptions::regression_degree). The value at v of the weighted
// least-squares polynomial of degree p in the tangent-plane coordinates of the samples is linear in the
// samples' values: sum_k l_k y_k with l_k = w_k e_1^T (X^T W X)^-1 x_k (the equivalent kernel), which
// reproduces every polynomial of degree <= p exactly. Degree 0 is the normalised weighted mean.
#pragma once

#include <utility>
#include <vector>

#include "framework/core/types.hpp"

namespace dtsl {

/// `taps`: (sample index into `positions`, weight w_k >= 0, normalised or not). Replaces each weight by
/// l_k for the highest degree <= `degree` the samples support: at least twice its parameters (3 for
/// linear, 6 for quadratic) and a design matrix whose smallest eigenvalue is above 1e-8 x its largest
/// (e.g. collinear samples cannot fix a plane). Tangent coordinates are taken in the plane through v
/// with normal n (unit), scaled by `scale` (> 0; the filter width) for conditioning. Returns the degree
/// used; at 0 the weights are divided by their sum.
int local_regression_weights(std::vector<std::pair<int, double>>& taps, const std::vector<Vec3>& positions,
                             const Vec3& v, const Vec3& n, double scale, int degree);

/// The weighted RMS misfit sqrt(sum_k w_k (y_k - p(x_k))^2 / sum_k w_k) of the weighted least-squares
/// polynomial p of exactly `degree` (0-2) to the samples' values y_k = values[k], with the weights w_k of
/// `taps` as given (before local_regression_weights); -1 when the samples cannot support that degree.
/// Noise-free samples of a field of degree <= `degree` give 0; a kink in the field (an edge between the
/// samples) a misfit proportional to its change of slope times the samples' spread.
double local_regression_misfit(const std::vector<std::pair<int, double>>& taps, const std::vector<Vec3>& positions,
                               const std::vector<double>& values, const Vec3& v, const Vec3& n, double scale,
                               int degree);

}  // namespace dtsl
