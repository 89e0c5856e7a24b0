// A 5x8 bitmap font (printable ASCII) for labels of figures: no font files, no FreeType.
#pragma once

#include <string>

#include "framework/render/image.hpp"

namespace dtsl::render {

/// Pixels per character cell at `scale` (6 x 8 per unit of scale: 5 columns plus a gap).
inline int char_width(int scale) { return 6 * scale; }
inline int char_height(int scale) { return 8 * scale; }
int text_width(const std::string& text, int scale);

/// Draws `text` with its top-left corner at (x, y); characters outside ' '..'~' are drawn as '?'.
void draw_text(Image& image, int x, int y, const std::string& text, Rgb colour, int scale = 1);

/// The same, rotated a quarter turn counter-clockwise (reading upwards), for vertical axis labels;
/// (x, y) is the bottom-left corner of the rotated text.
void draw_text_vertical(Image& image, int x, int y, const std::string& text, Rgb colour, int scale = 1);

}  // namespace dtsl::render
