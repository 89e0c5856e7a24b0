// Temporary debugging aid for the exploration test: writes an RGB image as an uncompressed PNG.
#pragma once
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace dtsl::test {

inline std::uint32_t png_crc(const unsigned char* data, std::size_t n, std::uint32_t crc = 0xffffffffu) {
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return crc;
}

inline void write_png(const std::string& path, int w, int h, const std::vector<unsigned char>& rgb) {
  std::vector<unsigned char> raw;
  for (int y = 0; y < h; ++y) {
    raw.push_back(0);
    raw.insert(raw.end(), rgb.begin() + std::size_t(y) * w * 3, rgb.begin() + std::size_t(y + 1) * w * 3);
  }
  std::vector<unsigned char> z = {0x78, 0x01};
  std::uint32_t a = 1, b = 0;
  for (unsigned char c : raw) { a = (a + c) % 65521; b = (b + a) % 65521; }
  for (std::size_t pos = 0; pos < raw.size();) {
    const std::size_t len = std::min<std::size_t>(65535, raw.size() - pos);
    z.push_back(pos + len == raw.size() ? 1 : 0);
    z.push_back(len & 0xff); z.push_back(len >> 8);
    z.push_back(~len & 0xff); z.push_back((~len >> 8) & 0xff);
    z.insert(z.end(), raw.begin() + pos, raw.begin() + pos + len);
    pos += len;
  }
  const std::uint32_t adler = (b << 16) | a;
  for (int s = 24; s >= 0; s -= 8) z.push_back((adler >> s) & 0xff);
  std::ofstream out(path, std::ios::binary);
  auto be32 = [&](std::uint32_t v) { for (int s = 24; s >= 0; s -= 8) out.put(char((v >> s) & 0xff)); };
  auto chunk = [&](const char* type, const std::vector<unsigned char>& d) {
    be32(std::uint32_t(d.size()));
    std::vector<unsigned char> td(type, type + 4);
    td.insert(td.end(), d.begin(), d.end());
    out.write(reinterpret_cast<const char*>(td.data()), td.size());
    be32(png_crc(td.data(), td.size()) ^ 0xffffffffu);
  };
  out.write("\x89PNG\r\n\x1a\n", 8);
  std::vector<unsigned char> ihdr;
  for (std::uint32_t v : {std::uint32_t(w), std::uint32_t(h)}) for (int s = 24; s >= 0; s -= 8) ihdr.push_back((v >> s) & 0xff);
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});
  chunk("IHDR", ihdr);
  chunk("IDAT", z);
  chunk("IEND", {});
}

}  // namespace dtsl::test
