// PCD (PCL's point cloud format), read and written by PCL itself, after a validation of our own:
// PCL's reader is not safe on malformed input (see validate_pcd).
#include "framework/io/pcd_io.hpp"

#include <pcl/PCLPointCloud2.h>
#include <pcl/io/pcd_io.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "framework/core/atomic_file.hpp"
#include "framework/core/error.hpp"
#include "framework/io/file_buffer.hpp"
#include "framework/io/text_lines.hpp"

namespace dtsl::io_detail {
namespace {

// PCL's header reader (1.13) does not stop at the DATA line: it goes on reading the lines after it,
// skipping blank ones and '#' comments, as header lines for as long as their first token (split at
// tab, CR and space, as PCL does) begins with a keyword; those overwrite what the real header said
// while the body still starts after DATA. A binary body that begins "# ...\nCOUNT 1 1 12222222222"
// then makes PCL read far past its buffer (found by fuzz/fuzz_pcd). Such a file is refused here.
void check_nothing_pcl_reads_as_header(const LineReader& data_line, std::string_view text) {
  static const char* const keywords[] = {"VERSION", "FIELDS", "COLUMNS", "SIZE",   "TYPE", "COUNT",
                                         "WIDTH",   "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};
  LineReader in(data_line.path(), text, data_line.end_offset(), data_line.number());
  while (in.next()) {
    const std::string_view line = in.line();
    if (line.empty()) continue;
    const std::string_view first = line.substr(0, line.find_first_of("\t\r "));
    if (!first.empty() && first[0] == '#') continue;
    for (const char* k : keywords)
      if (first.substr(0, std::strlen(k)) == k)
        in.fail("the data after the DATA line begins with what PCL would read as a header line (" +
                quoted(first) + ")");
    return;
  }
}

// PCL's PCD reader trusts its input: a truncated header or a count larger than the file makes it
// crash or allocate gigabytes. So the whole file is validated here first (header fields, sizes against
// the file size, every ascii value) and PCL only decodes files known to be well formed. Returns the
// number of points.
unsigned long long validate_pcd(const std::string& path, const std::string& text) {
  LineReader in(path, text);
  std::vector<std::string_view> names;
  std::vector<long long> sizes, counts;
  std::string types;
  long long width = -1, height = -1, points = -1;
  std::string_view data;
  for (std::size_t start = 0; !data.size() && in.next(); start = in.end_offset()) {
    // PCL skips only truly empty lines and splits at tab, CR and space alone: a line that starts with
    // a blank (even "\r" alone) or holds another control character ends its header there or splits
    // differently, so PCL would read another header than the one checked here (fuzz/fuzz_pcd).
    const std::string_view raw(text.data() + start, in.end_offset() - start);
    if (raw.empty() || raw[0] == '\n') continue;
    if (raw[0] == ' ' || raw[0] == '\t' || raw[0] == '\r')
      in.fail("a PCD header line must not start with a blank (PCL stops reading the header there)");
    for (const char c : in.line())
      if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r')
        in.fail("control character in the PCD header (PCL would read another header than this one)");
    Tokens tok(in.line());
    std::string_view key, t;
    if (!tok.next(key) || key[0] == '#') continue;
    std::vector<std::string_view> values;
    while (tok.next(t)) values.push_back(t);
    const auto need_per_field = [&](bool ready, const char* before) {
      if (!ready) in.fail(std::string(key) + " must come after " + before);
      if (values.size() != names.size())
        in.fail(std::string(key) + " has " + std::to_string(values.size()) + " entries for " +
                std::to_string(names.size()) + " fields");
    };
    const auto one_count = [&]() {
      if (values.size() != 1) in.fail(std::string(key) + " needs one number");
      const long long v = parse_integer(in, values[0], key == "WIDTH" ? "WIDTH" : key == "HEIGHT" ? "HEIGHT" : "POINTS");
      if (v < 0 || v > 0xffffffffLL) in.fail(std::string(key) + " out of range: " + quoted(values[0]));
      return v;
    };
    if (key == "VERSION") continue;
    if (key == "FIELDS" || key == "COLUMNS") {
      if (values.empty()) in.fail("FIELDS names no field");
      names = values;
    } else if (key == "SIZE") {
      need_per_field(!names.empty(), "FIELDS");
      sizes.clear();
      for (std::string_view v : values) {
        sizes.push_back(parse_integer(in, v, "a field size"));
        if (sizes.back() != 1 && sizes.back() != 2 && sizes.back() != 4 && sizes.back() != 8)
          in.fail("field size must be 1, 2, 4 or 8, got " + quoted(v));
      }
    } else if (key == "TYPE") {
      need_per_field(!sizes.empty(), "SIZE");
      types.clear();
      for (std::size_t k = 0; k < values.size(); ++k) {
        const std::string_view v = values[k];
        if (v != "I" && v != "U" && v != "F") in.fail("field type must be I, U or F, got " + quoted(v));
        if (v == "F" && sizes[k] != 4 && sizes[k] != 8) in.fail("a floating-point field must have size 4 or 8");
        types += v[0];
      }
    } else if (key == "COUNT") {
      need_per_field(!types.empty(), "TYPE");
      counts.clear();
      for (std::string_view v : values) {
        counts.push_back(parse_integer(in, v, "a field count"));
        if (counts.back() < 1 || counts.back() > (1 << 20)) in.fail("field count out of range: " + quoted(v));
      }
    } else if (key == "WIDTH") {
      width = one_count();
    } else if (key == "HEIGHT") {
      height = one_count();
    } else if (key == "POINTS") {
      points = one_count();
    } else if (key == "VIEWPOINT") {
      if (values.size() != 7) in.fail("VIEWPOINT needs 7 numbers (tx ty tz qw qx qy qz)");
      for (std::string_view v : values) parse_double(in, v, "a VIEWPOINT value");
    } else if (key == "DATA") {
      if (values.size() != 1 || (values[0] != "ascii" && values[0] != "binary" && values[0] != "binary_compressed"))
        in.fail("DATA must be ascii, binary or binary_compressed");
      data = values[0];
    } else {
      in.fail("unexpected PCD header line starting with " + quoted(key));
    }
  }
  if (data.empty()) throw FileError(path, "not a PCD file: the header has no DATA line", in.number());
  check_nothing_pcl_reads_as_header(in, text);
  if (types.empty()) in.fail("PCD header lacks FIELDS, SIZE or TYPE");
  if (counts.empty()) counts.assign(names.size(), 1);
  // A FIELDS line repeated after SIZE/TYPE/COUNT changes the number of fields (fuzz/fuzz_pcd).
  if (sizes.size() != names.size() || types.size() != names.size() || counts.size() != names.size())
    in.fail("FIELDS, SIZE, TYPE and COUNT must give one entry per field (a header line given twice?)");
  if (height < 0) height = 1;
  if (width < 0 || points < 0) in.fail("PCD header lacks WIDTH or POINTS");
  if (width * height != points)
    in.fail("WIDTH x HEIGHT (" + std::to_string(width) + " x " + std::to_string(height) + ") differs from POINTS (" +
            std::to_string(points) + ")");

  using Big = unsigned __int128;
  Big point_step = 0, values = 0;
  for (std::size_t k = 0; k < sizes.size(); ++k) {
    point_step += static_cast<Big>(sizes[k]) * counts[k];
    values += counts[k];
  }
  const std::size_t available = text.size() - in.end_offset();
  const auto promise = [&](const std::string& why) {
    in.fail("header promises " + std::to_string(points) + " points, " + why + " (truncated file or wrong count?)");
  };
  if (data == "ascii") {
    if (static_cast<Big>(points) * values * 2 > static_cast<Big>(available) + 1)  // a character and a separator each
      promise("but only " + std::to_string(available) + " bytes of text follow the header");
    // Every point on its own line with one number per value; PCL would otherwise read garbage as 0.
    long long seen = 0;
    while (in.next()) {
      Tokens tok(in.line());
      const std::size_t n = tok.count();
      if (n == 0) continue;
      if (seen == points) in.fail("unexpected data after the last point");
      if (n != static_cast<std::size_t>(values))
        in.fail("point " + std::to_string(seen) + " has " + std::to_string(n) + " values, the header says " +
                std::to_string(static_cast<unsigned long long>(values)));
      std::string_view t;
      double v;
      while (tok.next(t))
        if (to_double(t, v) == NumberStatus::malformed) in.fail("expected a number, got " + quoted(t));
      ++seen;
    }
    if (seen < points)
      throw FileError(path, "the file ends after " + std::to_string(seen) + " of the " + std::to_string(points) +
                                " points its header promises", in.number());
  } else if (data == "binary") {
    if (static_cast<Big>(points) * point_step > available)
      promise("of " + std::to_string(static_cast<unsigned long long>(point_step)) + " bytes each, but only " +
              std::to_string(available) + " bytes follow the header");
  } else {
    std::uint32_t block[2] = {0, 0};  // compressed and uncompressed sizes, little-endian
    if (available < sizeof block) in.fail("truncated binary data: no compressed block after the header");
    std::memcpy(block, text.data() + in.end_offset(), sizeof block);
    // LZF expands at most about 90 times; a larger claim cannot be honest.
    if (block[0] > available - sizeof block || static_cast<Big>(block[1]) != static_cast<Big>(points) * point_step ||
        static_cast<Big>(block[1]) > static_cast<Big>(block[0]) * 100 + 4096)
      promise("but its compressed block (" + std::to_string(block[0]) + " bytes, " + std::to_string(block[1]) +
              " uncompressed) does not match them or the file");
  }
  return static_cast<unsigned long long>(points);
}

double value_at(const std::uint8_t* p, std::uint8_t datatype) {
  switch (datatype) {
    case pcl::PCLPointField::INT8: { std::int8_t v; std::memcpy(&v, p, 1); return v; }
    case pcl::PCLPointField::UINT8: { std::uint8_t v; std::memcpy(&v, p, 1); return v; }
    case pcl::PCLPointField::INT16: { std::int16_t v; std::memcpy(&v, p, 2); return v; }
    case pcl::PCLPointField::UINT16: { std::uint16_t v; std::memcpy(&v, p, 2); return v; }
    case pcl::PCLPointField::INT32: { std::int32_t v; std::memcpy(&v, p, 4); return v; }
    case pcl::PCLPointField::UINT32: { std::uint32_t v; std::memcpy(&v, p, 4); return v; }
    case pcl::PCLPointField::FLOAT32: { float v; std::memcpy(&v, p, 4); return v; }
    case pcl::PCLPointField::FLOAT64: { double v; std::memcpy(&v, p, 8); return v; }
    default: return std::numeric_limits<double>::quiet_NaN();
  }
}

std::size_t datatype_size(std::uint8_t datatype) {
  switch (datatype) {
    case pcl::PCLPointField::INT8: case pcl::PCLPointField::UINT8: return 1;
    case pcl::PCLPointField::INT16: case pcl::PCLPointField::UINT16: return 2;
    case pcl::PCLPointField::INT32: case pcl::PCLPointField::UINT32: case pcl::PCLPointField::FLOAT32: return 4;
    case pcl::PCLPointField::FLOAT64: return 8;
    default: return 0;
  }
}

}  // namespace

PointCloud read_pcd(const std::string& path) {
  if (validate_pcd(path, load_file(path)) == 0) return {};  // PCL would only complain
  pcl::PCLPointCloud2 pc;
  int status = -1;
  try {
    status = pcl::io::loadPCDFile(path, pc);
  } catch (const std::exception& e) {
    throw FileError(path, std::string("PCL cannot read this PCD file: ") + e.what());
  }
  if (status != 0) throw FileError(path, "PCL cannot read this PCD file (malformed header or data)");

  // Offsets of the fields we need, checked against the point layout PCL reports.
  const char* names[6] = {"x", "y", "z", "normal_x", "normal_y", "normal_z"};
  int offset[6] = {-1, -1, -1, -1, -1, -1};
  std::uint8_t type[6] = {0, 0, 0, 0, 0, 0};
  for (const pcl::PCLPointField& f : pc.fields)
    for (int s = 0; s < 6; ++s)
      if (f.name == names[s] && offset[s] < 0) {
        const std::size_t bytes = datatype_size(f.datatype);
        if (bytes == 0 || f.count < 1 || f.offset + bytes > pc.point_step)
          throw FileError(path, std::string("field '") + names[s] + "' has an unsupported type or layout");
        offset[s] = static_cast<int>(f.offset);
        type[s] = f.datatype;
      }
  for (int s = 0; s < 3; ++s)
    if (offset[s] < 0) throw FileError(path, std::string("PCD file has no field '") + names[s] + "'");
  const bool normals = offset[3] >= 0 && offset[4] >= 0 && offset[5] >= 0;
  if (pc.is_bigendian) throw FileError(path, "big-endian PCD data is not supported");

  const std::size_t n = static_cast<std::size_t>(pc.width) * pc.height;
  if (pc.row_step < static_cast<std::size_t>(pc.width) * pc.point_step ||
      pc.data.size() < static_cast<std::size_t>(pc.row_step) * pc.height)
    throw FileError(path, "PCD data is shorter than its header promises");
  PointCloud cloud;
  cloud.points.reserve(n);
  if (normals) cloud.normals.reserve(n);
  std::size_t index = 0;
  for (std::size_t r = 0; r < pc.height; ++r)
    for (std::size_t c = 0; c < pc.width; ++c, ++index) {
      const std::uint8_t* p = pc.data.data() + r * pc.row_step + c * pc.point_step;
      double v[6];
      for (int s = 0; s < (normals ? 6 : 3); ++s) {
        v[s] = value_at(p + offset[s], type[s]);
        if (!std::isfinite(v[s]))
          throw FileError(path, "point " + std::to_string(index) +
                                    " has a NaN or infinite coordinate (PCD marks missing measurements with NaN; "
                                    "remove such points first)");
      }
      cloud.points.emplace_back(v[0], v[1], v[2]);
      if (normals) cloud.normals.emplace_back(v[3], v[4], v[5]);
    }
  return cloud;
}

void write_pcd(const std::string& path, const PointCloud& cloud, bool binary) {
  const bool normals = cloud.has_normals();
  pcl::PCLPointCloud2 pc;
  const char* names[6] = {"x", "y", "z", "normal_x", "normal_y", "normal_z"};
  const int nfields = normals ? 6 : 3;
  for (int s = 0; s < nfields; ++s) {
    pcl::PCLPointField f;
    f.name = names[s];
    f.offset = static_cast<std::uint32_t>(4 * s);
    f.datatype = pcl::PCLPointField::FLOAT32;
    f.count = 1;
    pc.fields.push_back(f);
  }
  pc.height = 1;
  pc.width = static_cast<std::uint32_t>(cloud.size());
  pc.point_step = static_cast<std::uint32_t>(4 * nfields);
  pc.row_step = pc.point_step * pc.width;
  pc.is_dense = true;
  pc.is_bigendian = false;
  pc.data.resize(static_cast<std::size_t>(pc.row_step));
  for (std::size_t i = 0; i < cloud.size(); ++i)
    for (int s = 0; s < nfields; ++s) {
      const double x = s < 3 ? cloud.points[i][s] : cloud.normals[i][s - 3];
      if (std::abs(x) > std::numeric_limits<float>::max())
        throw FileError(path, "point " + std::to_string(i) + " does not fit PCD's float32 coordinates");
      const float v = static_cast<float>(x);
      std::memcpy(pc.data.data() + i * pc.point_step + 4 * s, &v, 4);
    }

  const std::string tmp = temporary_path_for(path);
  int status = -1;
  try {
    status = pcl::io::savePCDFile(tmp, pc, Eigen::Vector4f::Zero(), Eigen::Quaternionf::Identity(), binary);
  } catch (const std::exception& e) {
    std::remove(tmp.c_str());
    throw FileError(path, std::string("PCL cannot write it: ") + e.what());
  }
  if (status != 0) {
    std::remove(tmp.c_str());
    throw FileError(path, "PCL cannot write it");
  }
  commit_temporary(tmp, path);
}

}  // namespace dtsl::io_detail
