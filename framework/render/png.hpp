// PNG output through libpng: the only file format the figures need.
#pragma once

#include <string>

#include "framework/render/image.hpp"

namespace dtsl::render {

/// Writes `image` as an 8-bit RGB PNG, atomically (a temporary file renamed into place). FileError
/// naming `path` on failure; an empty image is an error.
void write_png(const std::string& path, const Image& image);

/// Reads the width and height from a PNG's header (for tests and the report). FileError if `path`
/// is not a PNG.
std::pair<int, int> png_size(const std::string& path);

}  // namespace dtsl::render
