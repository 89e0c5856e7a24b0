// Line and bar charts drawn with the rasteriser's image and bitmap font: axes, "nice" ticks, labels,
// a legend. Enough for convergence histories, phase timings and metric-versus-parameter plots.
#pragma once

#include <string>
#include <vector>

#include "framework/render/image.hpp"

namespace dtsl::render {

struct Series {
  std::string name;
  std::vector<double> x, y;  ///< same length; non-finite values (and y <= 0 on a log axis) are skipped
  bool markers = true;
};

struct LineChart {
  std::string title, x_label, y_label;
  bool log_y = false;
  bool integer_x = false;  ///< x ticks only at whole numbers (iterations)
  /// Non-empty: the x axis is categorical; x values are indices into these labels.
  std::vector<std::string> x_categories;
  std::vector<Series> series;
  int width = 900, height = 540;

  /// The chart; "no data" in the plot area if nothing is finite.
  Image draw() const;
};

/// Horizontal bars, one row per label; each row a stack of segments (one per segment name).
struct BarChart {
  std::string title, value_label;
  std::vector<std::string> rows;
  std::vector<std::string> segments;           ///< legend entries; one segment name = no legend
  std::vector<std::vector<double>> values;     ///< values[row][segment], >= 0
  int width = 900;
  int row_height = 28;                          ///< pixels per bar

  Image draw() const;
};

/// Tick positions for [lo, hi]: about `target` round values (1, 2, 5 x 10^k).
std::vector<double> nice_ticks(double lo, double hi, int target = 6);

/// A label for a tick value with as many digits as the tick spacing `step` needs: fixed ("0.002",
/// "120") unless `magnitude` (the axis' largest |value|; 0: v's own) calls for scientific ("2.105e-04").
std::string tick_label(double v, double step, double magnitude);
/// Labels of a whole axis in one style.
std::vector<std::string> tick_labels(const std::vector<double>& ticks);

}  // namespace dtsl::render
