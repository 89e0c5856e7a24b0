#include "framework/render/chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "framework/render/font.hpp"

namespace dtsl::render {

namespace {

const Rgb kBlack{30, 30, 30}, kGrid{225, 225, 225}, kGrey{110, 110, 110};
constexpr int kFont = 2;  // font scale of every label

std::string fit(const std::string& s, int max_pixels) {
  const int n = std::max(1, max_pixels / char_width(kFont));
  return static_cast<int>(s.size()) <= n ? s : s.substr(0, std::max(1, n - 2)) + "..";
}

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!(hi > lo)) return {lo};
  const double raw = (hi - lo) / std::max(target, 1);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  std::vector<double> out;
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + step * 1e-9; v += step)
    out.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
  return out;
}

std::string tick_label(double v, double step, double magnitude) {
  char buf[48];
  if (v == 0) return "0";
  const double a = std::abs(v);
  if (!(step > 0) || !std::isfinite(step)) step = a;
  if (!(magnitude > 0)) magnitude = a;
  const int s_exp = static_cast<int>(std::floor(std::log10(step) + 1e-9));
  if (magnitude >= 1e5 || magnitude < 1e-3) {  // scientific, with as many digits as the step needs
    const int v_exp = static_cast<int>(std::floor(std::log10(a) + 1e-9));
    std::snprintf(buf, sizeof buf, "%.*e", std::clamp(v_exp - s_exp, 0, 8), v);
  } else {
    std::snprintf(buf, sizeof buf, "%.*f", std::clamp(-s_exp, 0, 10), v);
  }
  return buf;
}

std::vector<std::string> tick_labels(const std::vector<double>& ticks) {
  double magnitude = 0;
  for (double t : ticks) magnitude = std::max(magnitude, std::abs(t));
  const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : magnitude;
  std::vector<std::string> out;
  for (double t : ticks) out.push_back(tick_label(t, step, magnitude));
  return out;
}

Image LineChart::draw() const {
  Image img(width, height);
  const int left = 20 + char_height(kFont) + 8 * char_width(kFont) + 12, right = 24;
  const int top = 16 + char_height(kFont) + 12;
  // Legend below the plot: one line per series, up to 8.
  const std::size_t legend_lines = std::min<std::size_t>(series.size(), 8);
  const int legend_cols = series.size() > 4 ? 2 : 1;
  const int legend_h = static_cast<int>((legend_lines + legend_cols - 1) / legend_cols) * (char_height(kFont) + 6);
  const int bottom = 12 + 2 * (char_height(kFont) + 8) + legend_h;
  int x0 = left;  // widened below if the y tick labels need it
  const int x1 = width - right, y0 = top, y1 = height - bottom;
  const std::string shown_title = fit(title, width - 20);
  draw_text(img, (width - text_width(shown_title, kFont)) / 2, 12, shown_title, kBlack, kFont);

  double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin, ymin = xmin, ymax = -xmin;
  auto usable = [&](double x, double y) { return std::isfinite(x) && std::isfinite(y) && (!log_y || y > 0); };
  for (const Series& s : series)
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
      if (usable(s.x[i], s.y[i])) {
        const double y = log_y ? std::log10(s.y[i]) : s.y[i];
        xmin = std::min(xmin, s.x[i]), xmax = std::max(xmax, s.x[i]), ymin = std::min(ymin, y), ymax = std::max(ymax, y);
      }
  if (!std::isfinite(xmin)) {
    img.rect_outline(x0, y0, x1, y1, kBlack);
    draw_text(img, (x0 + x1 - text_width("no data", kFont)) / 2, (y0 + y1) / 2, "no data", kGrey, kFont);
    return img;
  }
  if (!x_categories.empty()) xmin = -0.5, xmax = x_categories.size() - 0.5;
  if (xmax - xmin < 1e-12) xmin -= 0.5, xmax += 0.5;
  if (ymax - ymin < 1e-6 * std::max(1e-300, std::abs(ymax)) || ymax - ymin < 1e-300) {  // constant data
    const double pad = log_y ? 0.5 : std::max(std::abs(ymax) * 0.1, 1e-9);
    ymin -= pad, ymax += pad;
  }
  const double ypad = 0.05 * (ymax - ymin);
  ymin -= ypad, ymax += ypad;
  if (!log_y && ymin < 0 && ymin + ypad >= 0) ymin = 0;  // non-negative data: axis starts at 0
  const double xpad = x_categories.empty() ? 0.03 * (xmax - xmin) : 0.0;
  xmin -= xpad, xmax += xpad;
  auto px = [&](double x) { return x0 + (x - xmin) / (xmax - xmin) * (x1 - x0); };
  auto py = [&](double y) { return y1 - (y - ymin) / (ymax - ymin) * (y1 - y0); };

  // Y ticks (log: decades, with 2 and 5 if there are few decades).
  std::vector<std::pair<double, std::string>> yt;
  if (log_y) {
    const int d0 = static_cast<int>(std::floor(ymin)), d1 = static_cast<int>(std::ceil(ymax));
    for (int d = d0; d <= d1; ++d)
      for (double m : (d1 - d0 <= 2 ? std::vector<double>{1, 2, 5} : std::vector<double>{1})) {
        const double v = std::log10(m) + d;
        if (v >= ymin && v <= ymax) yt.push_back({v, tick_label(m * std::pow(10.0, d), m * std::pow(10.0, d), 0.0)});
      }
  } else {
    const std::vector<double> t = nice_ticks(ymin, ymax);
    const std::vector<std::string> labels = tick_labels(t);
    for (std::size_t i = 0; i < t.size(); ++i) yt.push_back({t[i], labels[i]});
  }
  int widest = 0;
  for (const auto& tick : yt) widest = std::max(widest, text_width(tick.second, kFont));
  x0 = std::max(x0, 20 + char_height(kFont) + widest + 16);
  for (const auto& [v, label] : yt) {
    const double y = py(v);
    img.line(x0 + 1, y, x1 - 1, y, kGrid);
    img.line(x0 - 5, y, x0, y, kBlack);
    draw_text(img, x0 - 8 - text_width(label, kFont), static_cast<int>(y) - char_height(kFont) / 2, label, kBlack, kFont);
  }
  // X ticks.
  std::vector<std::pair<double, std::string>> xt;
  if (!x_categories.empty()) {
    for (std::size_t i = 0; i < x_categories.size(); ++i) xt.push_back({static_cast<double>(i), x_categories[i]});
  } else {
    std::vector<double> t;
    for (double v : nice_ticks(xmin, xmax, 8))
      if (!integer_x || std::abs(v - std::round(v)) < 1e-9) t.push_back(v);
    const std::vector<std::string> labels = tick_labels(t);
    for (std::size_t i = 0; i < t.size(); ++i) xt.push_back({t[i], labels[i]});
  }
  const int slot = std::max(1, (x1 - x0) / std::max<int>(1, xt.size()));
  for (const auto& [v, label0] : xt) {
    const double x = px(v);
    const std::string label = x_categories.empty() ? label0 : fit(label0, slot - 4);
    img.line(x, y0 + 1, x, y1 - 1, kGrid);
    img.line(x, y1, x, y1 + 5, kBlack);
    draw_text(img, static_cast<int>(x) - text_width(label, kFont) / 2, y1 + 8, label, kBlack, kFont);
  }
  img.rect_outline(x0, y0, x1, y1, kBlack);
  draw_text(img, (x0 + x1 - text_width(x_label, kFont)) / 2, y1 + 8 + char_height(kFont) + 8, fit(x_label, x1 - x0),
            kBlack, kFont);
  const std::string yl = fit(y_label + (log_y ? " (log)" : ""), y1 - y0);
  draw_text_vertical(img, 12, (y0 + y1 + text_width(yl, kFont)) / 2, yl, kBlack, kFont);

  // Series.
  for (std::size_t k = 0; k < series.size(); ++k) {
    const Series& s = series[k];
    const Rgb c = palette(k);
    bool have_prev = false;
    double qx = 0, qy = 0;
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!usable(s.x[i], s.y[i])) {
        have_prev = false;
        continue;
      }
      const double x = px(s.x[i]), y = py(log_y ? std::log10(s.y[i]) : s.y[i]);
      if (have_prev) img.line(qx, qy, x, y, c, 2.5);
      if (s.markers) img.fill_rect(static_cast<int>(x) - 3, static_cast<int>(y) - 3, static_cast<int>(x) + 4, static_cast<int>(y) + 4, c);
      qx = x, qy = y, have_prev = true;
    }
  }
  // Legend.
  const int col_w = (x1 - x0) / legend_cols;
  for (std::size_t k = 0; k < legend_lines; ++k) {
    const int lx = x0 + static_cast<int>(k % legend_cols) * col_w;
    const int ly = y1 + 2 * (char_height(kFont) + 8) + 8 + static_cast<int>(k / legend_cols) * (char_height(kFont) + 6);
    img.fill_rect(lx, ly + 3, lx + 24, ly + char_height(kFont) - 3, palette(k));
    const std::string name = k == 7 && series.size() > 8 ? "... (" + std::to_string(series.size() - 7) + " more)" : series[k].name;
    draw_text(img, lx + 32, ly, fit(name, col_w - 40), kBlack, kFont);
  }
  return img;
}

Image BarChart::draw() const {
  const bool legend = segments.size() > 1;
  std::size_t label_chars = 4;
  for (const std::string& r : rows) label_chars = std::max(label_chars, r.size());
  label_chars = std::min<std::size_t>(label_chars, 40);
  const int left = 16 + static_cast<int>(label_chars) * char_width(kFont) + 8, right = 24 + 7 * char_width(kFont);
  const int top = 16 + char_height(kFont) + 12;
  // Legend entries flow left to right and wrap at the plot's right edge.
  std::vector<std::pair<int, int>> legend_at;  // (x, line) per segment
  if (legend) {
    int lx = left, line = 0;
    for (const std::string& name : segments) {
      const int w = 26 + text_width(name, kFont) + 24;
      if (lx > left && lx + w > width - 8) lx = left, ++line;
      legend_at.push_back({lx, line});
      lx += w;
    }
  }
  const int legend_h = legend ? (legend_at.back().second + 1) * (char_height(kFont) + 8) + 8 : 0;
  const int plot_h = std::max<int>(1, rows.size()) * row_height;
  const int height = top + plot_h + 2 * (char_height(kFont) + 8) + legend_h + 12;
  Image img(width, height);
  const int x0 = left, x1 = width - right, y0 = top, y1 = top + plot_h;
  const std::string shown_title = fit(title, width - 20);
  draw_text(img, (width - text_width(shown_title, kFont)) / 2, 12, shown_title, kBlack, kFont);

  double vmax = 0;
  for (const auto& row : values) {
    double sum = 0;
    for (double v : row)
      if (std::isfinite(v) && v > 0) sum += v;
    vmax = std::max(vmax, sum);
  }
  if (!(vmax > 0)) vmax = 1;
  const std::vector<double> ticks = nice_ticks(0, vmax * 1.05, 6);
  const double top_value = std::max(vmax * 1.05, ticks.back());
  auto px = [&](double v) { return x0 + v / top_value * (x1 - x0); };
  const std::vector<std::string> labels = tick_labels(ticks);
  for (std::size_t i = 0; i < ticks.size(); ++i) {
    const double t = ticks[i];
    img.line(px(t), y0, px(t), y1, kGrid);
    img.line(px(t), y1, px(t), y1 + 5, kBlack);
    const std::string& label = labels[i];
    draw_text(img, static_cast<int>(px(t)) - text_width(label, kFont) / 2, y1 + 8, label, kBlack, kFont);
  }
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const int ry = y0 + static_cast<int>(r) * row_height;
    draw_text(img, x0 - 8 - text_width(fit(rows[r], label_chars * char_width(kFont)), kFont),
              ry + (row_height - char_height(kFont)) / 2, fit(rows[r], label_chars * char_width(kFont)), kBlack, kFont);
    double acc = 0;
    if (r < values.size())
      for (std::size_t s = 0; s < values[r].size(); ++s) {
        const double v = values[r][s];
        if (!std::isfinite(v) || v <= 0) continue;
        img.fill_rect(static_cast<int>(px(acc)), ry + 4, static_cast<int>(std::ceil(px(acc + v))), ry + row_height - 4,
                      palette(legend ? s : 0));
        acc += v;
      }
    char total[32];
    std::snprintf(total, sizeof total, "%.3g", acc);
    draw_text(img, static_cast<int>(px(acc)) + 6, ry + (row_height - char_height(kFont)) / 2, total, kGrey, kFont);
  }
  img.line(x0, y0, x0, y1, kBlack);
  img.line(x0, y1, x1, y1, kBlack);
  draw_text(img, (x0 + x1 - text_width(value_label, kFont)) / 2, y1 + 8 + char_height(kFont) + 8, value_label, kBlack, kFont);
  for (std::size_t s = 0; s < legend_at.size(); ++s) {
    const int lx = legend_at[s].first;
    const int ly = y1 + 2 * (char_height(kFont) + 8) + 12 + legend_at[s].second * (char_height(kFont) + 8);
    img.fill_rect(lx, ly + 3, lx + 20, ly + char_height(kFont) - 3, palette(s));
    draw_text(img, lx + 26, ly, segments[s], kBlack, kFont);
  }
  return img;
}

}  // namespace dtsl::render
