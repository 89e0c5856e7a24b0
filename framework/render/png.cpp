#include "framework/render/png.hpp"

#include <png.h>

#include <cstdio>
#include <fstream>
#include <vector>

#include "framework/core/atomic_file.hpp"
#include "framework/core/error.hpp"

namespace dtsl::render {

void write_png(const std::string& path, const Image& image) {
  if (image.width() <= 0 || image.height() <= 0) throw FileError(path, "cannot write an empty image");
  const std::string tmp = temporary_path_for(path);
  FILE* fp = std::fopen(tmp.c_str(), "wb");
  if (!fp) throw FileError(path, "cannot open for writing");
  std::vector<png_byte> row(static_cast<std::size_t>(image.width()) * 3);  // before setjmp: no destructor skipped
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    std::fclose(fp);
    std::remove(tmp.c_str());
    throw FileError(path, "libpng failed to write the image");
  }
  png_init_io(png, fp);
  png_set_IHDR(png, info, image.width(), image.height(), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const Rgb& p = image.at(x, y);
      row[3 * x] = p.r, row[3 * x + 1] = p.g, row[3 * x + 2] = p.b;
    }
    png_write_row(png, row.data());
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  const bool ok = std::fflush(fp) == 0;
  std::fclose(fp);
  if (!ok) {
    std::remove(tmp.c_str());
    throw FileError(path, "write failed (disk full?)");
  }
  commit_temporary(tmp, path);
}

std::pair<int, int> png_size(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char h[24] = {};
  if (!in.read(reinterpret_cast<char*>(h), 24) || png_sig_cmp(h, 0, 8) != 0) throw FileError(path, "not a PNG file");
  auto be32 = [&](int o) { return (h[o] << 24) | (h[o + 1] << 16) | (h[o + 2] << 8) | h[o + 3]; };
  return {be32(16), be32(20)};
}

}  // namespace dtsl::render
