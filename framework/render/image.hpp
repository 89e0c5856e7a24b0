// An 8-bit RGB raster with the few drawing primitives the figures need (filled rectangles, lines,
// blending). Pixel (0, 0) is the top-left corner; rows go down.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace dtsl::render {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

/// From components in [0, 1] (clamped).
Rgb rgb(double r, double g, double b);

/// A colour of a qualitative palette (10 colours, repeating), for series and stacked bars.
Rgb palette(std::size_t i);

class Image {
 public:
  Image() = default;
  Image(int width, int height, Rgb fill = {255, 255, 255});

  int width() const { return width_; }
  int height() const { return height_; }
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }
  Rgb& at(int x, int y) { return pixels_[static_cast<std::size_t>(y) * width_ + x]; }
  const Rgb& at(int x, int y) const { return pixels_[static_cast<std::size_t>(y) * width_ + x]; }
  const std::vector<Rgb>& pixels() const { return pixels_; }

  /// Clipped writes; `alpha` in [0, 1] blends over what is there.
  void set(int x, int y, Rgb c, double alpha = 1.0);
  void fill_rect(int x0, int y0, int x1, int y1, Rgb c, double alpha = 1.0);  ///< [x0, x1) x [y0, y1)
  void rect_outline(int x0, int y0, int x1, int y1, Rgb c);
  /// A line of the given width (pixels), end points included.
  void line(double x0, double y0, double x1, double y1, Rgb c, double width = 1.0);
  /// Copies `src` with its top-left corner at (x, y), clipped.
  void paste(const Image& src, int x, int y);
  /// Box-filter downsampling by an integer factor (anti-aliasing of a supersampled render).
  Image downsample(int factor) const;

 private:
  int width_ = 0, height_ = 0;
  std::vector<Rgb> pixels_;
};

}  // namespace dtsl::render
