// The univariate cubic B-spline on five simple knots: the factor of every T-spline blending function
// (docs/design.md §1: B_i(x) = N[u_i](x) N[v_i](y) N[w_i](z)). Stored as its four polynomial pieces so that
// evaluating value, first and second derivative is one interval search and three Horner schemes —
// the inner loop of every T-spline evaluation.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "framework/core/error.hpp"

namespace dtsl {

using KnotValues = std::array<double, 5>;

/// Cox–de Boor recursion for N[t0..t4] or its first or second derivative (`derivative` 0, 1, 2) at x,
/// on the half-open support [t0, t4). Slow and obviously right: the reference the tests compare the
/// piecewise form against.
inline double cox_de_boor(const KnotValues& t, double x, int derivative) {
  // n[p][j] = N_{j,p}(x) and its derivatives, built degree by degree; d[p][j] / dd[p][j] likewise.
  double n[4][4] = {}, d[4][4] = {}, dd[4][4] = {};
  for (int j = 0; j < 4; ++j) n[0][j] = (t[j] <= x && x < t[j + 1]) ? 1.0 : 0.0;
  for (int p = 1; p <= 3; ++p) {
    for (int j = 0; j + p + 1 <= 4; ++j) {
      const double a = 1.0 / (t[j + p] - t[j]), b = 1.0 / (t[j + p + 1] - t[j + 1]);
      n[p][j] = (x - t[j]) * a * n[p - 1][j] + (t[j + p + 1] - x) * b * n[p - 1][j + 1];
      d[p][j] = p * (a * n[p - 1][j] - b * n[p - 1][j + 1]);
      dd[p][j] = p * (a * d[p - 1][j] - b * d[p - 1][j + 1]);
    }
  }
  return derivative == 0 ? n[3][0] : derivative == 1 ? d[3][0] : dd[3][0];
}

/// N[t0..t4](x), the cubic B-spline with knots t0 < t1 < t2 < t3 < t4 (simple knots, so C2), zero
/// outside [t0, t4).
class CubicBSpline {
 public:
  /// Throws AlgorithmError unless the knots strictly increase (a multiple knot would break the C2
  /// continuity the paper relies on, §2.1).
  explicit CubicBSpline(const KnotValues& t) : t_(t) {
    for (int k = 0; k < 4; ++k)
      if (!(t[k] < t[k + 1]))
        throw AlgorithmError("cubic B-spline: knots must strictly increase, knot " +
                             std::to_string(k + 1) + " does not");
    // Piece s, on [t_s, t_{s+1}), as a polynomial in y = x - t_s: the Cox–de Boor recursion carried out
    // on polynomials (coefficient arrays) instead of numbers.
    for (int s = 0; s < 4; ++s) {
      double p[4][4][4] = {};  // p[degree][j][power]
      p[0][s][0] = 1.0;
      for (int deg = 1; deg <= 3; ++deg) {
        for (int j = 0; j + deg + 1 <= 4; ++j) {
          // N_{j,deg} = (y + t_s - t_j) a N_{j,deg-1} + (t_{j+deg+1} - t_s - y) b N_{j+1,deg-1}
          const double a = 1.0 / (t[j + deg] - t[j]), b = 1.0 / (t[j + deg + 1] - t[j + 1]);
          const double a0 = (t[s] - t[j]) * a, b0 = (t[j + deg + 1] - t[s]) * b;
          for (int k = 0; k < 4; ++k) {
            double c = a0 * p[deg - 1][j][k] + b0 * p[deg - 1][j + 1][k];
            if (k > 0) c += a * p[deg - 1][j][k - 1] - b * p[deg - 1][j + 1][k - 1];
            p[deg][j][k] = c;
          }
        }
      }
      for (int k = 0; k < 4; ++k) c_[s][k] = p[3][0][k];
    }
  }

  const KnotValues& knots() const { return t_; }

  /// The Greville abscissa: the mean of the three inner knots (docs/design.md §1, quasi-interpolation).
  double greville() const { return (t_[1] + t_[2] + t_[3]) / 3.0; }

  /// N(x), and N'(x) if Order >= 1, and N''(x) if Order >= 2 (the other outputs are left untouched).
  template <int Order>
  void evaluate(double x, double& value, double& d1, double& d2) const {
    // Branch-free: in the T-spline inner loop x falls inside or outside the support unpredictably.
    const int s = int(x >= t_[1]) + int(x >= t_[2]) + int(x >= t_[3]);
    const double inside = (x >= t_[0] && x < t_[4]) ? 1.0 : 0.0;  // also 0 for NaN
    const double y = inside != 0.0 ? x - t_[s] : 0.0;              // no inf * 0 far outside
    const double* c = c_[s];
    // N >= 0; near t4 the last piece's polynomial can round to -1e-17, clamp that to 0.
    value = inside * std::max(0.0, ((c[3] * y + c[2]) * y + c[1]) * y + c[0]);
    if (Order >= 1) d1 = inside * ((3.0 * c[3] * y + 2.0 * c[2]) * y + c[1]);
    if (Order >= 2) d2 = inside * (6.0 * c[3] * y + 2.0 * c[2]);
  }

  double value(double x) const {
    double v, d1, d2;
    evaluate<0>(x, v, d1, d2);
    return v;
  }

 private:
  KnotValues t_;
  double c_[4][4];  // c_[s][k]: coefficient of (x - t_s)^k on piece s
};

}  // namespace dtsl
