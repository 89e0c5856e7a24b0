#include "framework/render/image.hpp"

#include <algorithm>
#include <cmath>

namespace dtsl::render {

namespace {
std::uint8_t channel(double v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }
}  // namespace

Rgb rgb(double r, double g, double b) { return {channel(r), channel(g), channel(b)}; }

Rgb palette(std::size_t i) {
  static const Rgb colours[] = {{31, 119, 180}, {255, 127, 14}, {44, 160, 44},  {214, 39, 40},  {148, 103, 189},
                                {140, 86, 75},  {227, 119, 194}, {127, 127, 127}, {188, 189, 34}, {23, 190, 207}};
  return colours[i % 10];
}

Image::Image(int width, int height, Rgb fill)
    : width_(std::max(width, 0)), height_(std::max(height, 0)),
      pixels_(static_cast<std::size_t>(width_) * height_, fill) {}

void Image::set(int x, int y, Rgb c, double alpha) {
  if (!inside(x, y)) return;
  Rgb& p = at(x, y);
  if (alpha >= 1.0) {
    p = c;
    return;
  }
  if (alpha <= 0.0) return;
  auto mix = [alpha](std::uint8_t a, std::uint8_t b) {
    return static_cast<std::uint8_t>(std::lround(a * (1.0 - alpha) + b * alpha));
  };
  p = {mix(p.r, c.r), mix(p.g, c.g), mix(p.b, c.b)};
}

void Image::fill_rect(int x0, int y0, int x1, int y1, Rgb c, double alpha) {
  x0 = std::max(x0, 0), y0 = std::max(y0, 0), x1 = std::min(x1, width_), y1 = std::min(y1, height_);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) set(x, y, c, alpha);
}

void Image::rect_outline(int x0, int y0, int x1, int y1, Rgb c) {
  for (int x = x0; x <= x1; ++x) set(x, y0, c), set(x, y1, c);
  for (int y = y0; y <= y1; ++y) set(x0, y, c), set(x1, y, c);
}

void Image::line(double x0, double y0, double x1, double y1, Rgb c, double width) {
  // Distance-to-segment coverage over the segment's box: cheap, anti-aliased, any width.
  const double half = 0.5 * std::max(width, 0.5);
  const int bx0 = static_cast<int>(std::floor(std::min(x0, x1) - half - 1));
  const int bx1 = static_cast<int>(std::ceil(std::max(x0, x1) + half + 1));
  const int by0 = static_cast<int>(std::floor(std::min(y0, y1) - half - 1));
  const int by1 = static_cast<int>(std::ceil(std::max(y0, y1) + half + 1));
  const double dx = x1 - x0, dy = y1 - y0, len2 = dx * dx + dy * dy;
  for (int y = std::max(by0, 0); y <= std::min(by1, height_ - 1); ++y)
    for (int x = std::max(bx0, 0); x <= std::min(bx1, width_ - 1); ++x) {
      double t = len2 > 0 ? ((x - x0) * dx + (y - y0) * dy) / len2 : 0.0;
      t = std::clamp(t, 0.0, 1.0);
      const double d = std::hypot(x - (x0 + t * dx), y - (y0 + t * dy));
      const double cover = std::clamp(half + 0.5 - d, 0.0, 1.0);
      if (cover > 0) set(x, y, c, cover);
    }
}

void Image::paste(const Image& src, int x, int y) {
  for (int j = 0; j < src.height(); ++j)
    for (int i = 0; i < src.width(); ++i)
      if (inside(x + i, y + j)) at(x + i, y + j) = src.at(i, j);
}

Image Image::downsample(int factor) const {
  if (factor <= 1) return *this;
  Image out(width_ / factor, height_ / factor);
  const int n = factor * factor;
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x) {
      int r = 0, g = 0, b = 0;
      for (int j = 0; j < factor; ++j)
        for (int i = 0; i < factor; ++i) {
          const Rgb& p = at(x * factor + i, y * factor + j);
          r += p.r, g += p.g, b += p.b;
        }
      out.at(x, y) = {static_cast<std::uint8_t>(r / n), static_cast<std::uint8_t>(g / n),
                      static_cast<std::uint8_t>(b / n)};
    }
  return out;
}

}  // namespace dtsl::render
