// PLY (the Stanford polygon format) with ascii, binary_little_endian and binary_big_endian bodies.
// Only the vertex element (x y z, optional nx ny nz) and the face element's vertex_indices (or
// vertex_index) list are used; every other element and property, scalar or list, is skipped according
// to its declared type. Counts from the header are checked against the bytes that follow it before
// anything is allocated.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "framework/core/atomic_file.hpp"
#include "framework/core/error.hpp"
#include "framework/io/formats.hpp"
#include "framework/io/text_lines.hpp"
#include "framework/io/text_writer.hpp"

namespace dtsl::io_detail {
namespace {

enum class Type { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

bool type_from_name(std::string_view name, Type& type) {
  struct Entry {
    const char* name;
    Type type;
  };
  static const Entry names[] = {
      {"char", Type::int8},     {"int8", Type::int8},       {"uchar", Type::uint8},     {"uint8", Type::uint8},
      {"short", Type::int16},   {"int16", Type::int16},     {"ushort", Type::uint16},   {"uint16", Type::uint16},
      {"int", Type::int32},     {"int32", Type::int32},     {"uint", Type::uint32},     {"uint32", Type::uint32},
      {"float", Type::float32}, {"float32", Type::float32}, {"double", Type::float64}, {"float64", Type::float64}};
  for (const Entry& e : names)
    if (name == e.name) {
      type = e.type;
      return true;
    }
  return false;
}

std::size_t size_of(Type t) {
  switch (t) {
    case Type::int8:
    case Type::uint8:
      return 1;
    case Type::int16:
    case Type::uint16:
      return 2;
    case Type::int32:
    case Type::uint32:
    case Type::float32:
      return 4;
    case Type::float64:
      return 8;
  }
  return 8;
}

bool is_integer(Type t) { return t != Type::float32 && t != Type::float64; }

struct Property {
  std::string name;
  Type type = Type::float32;  ///< the value type (of the entries, for a list)
  bool is_list = false;
  Type count_type = Type::uint8;  ///< lists only
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  long line = 0;  ///< header line that declares it, for messages
  std::vector<Property> properties;
};

enum class Encoding { ascii, binary_little_endian, binary_big_endian };

struct Header {
  Encoding encoding = Encoding::ascii;
  std::vector<Element> elements;
  std::size_t body_offset = 0;  ///< first byte after the end_header line
  long end_header_line = 0;
};

Header parse_header(const std::string& path, std::string_view text) {
  LineReader in(path, text);
  if (!in.next() || trim(in.line()) != "ply")
    in.fail("not a PLY file: the first line must be 'ply'");
  Header h;
  bool have_format = false;
  for (;;) {
    if (!in.next()) throw FileError(path, "PLY header has no 'end_header' line");
    Tokens tok(in.line());
    std::string_view word;
    if (!tok.next(word)) continue;  // a blank header line is harmless
    if (word == "end_header") break;
    if (word == "comment" || word == "obj_info") continue;
    if (word == "format") {
      std::string_view enc;
      tok.next(enc);
      if (enc == "ascii") h.encoding = Encoding::ascii;
      else if (enc == "binary_little_endian") h.encoding = Encoding::binary_little_endian;
      else if (enc == "binary_big_endian") h.encoding = Encoding::binary_big_endian;
      else in.fail("unknown PLY format " + quoted(enc) + " (ascii, binary_little_endian or binary_big_endian)");
      have_format = true;
    } else if (word == "element") {
      Element e;
      std::string_view name, count;
      if (!tok.next(name) || !tok.next(count)) in.fail("expected 'element <name> <count>'");
      const long long n = parse_integer(in, count, "the element count");
      if (n < 0) in.fail("negative element count " + quoted(count));
      e.name = std::string(name);
      e.count = static_cast<std::uint64_t>(n);
      e.line = in.number();
      h.elements.push_back(std::move(e));
    } else if (word == "property") {
      if (h.elements.empty()) in.fail("'property' before any 'element' line");
      Property p;
      std::string_view type, name;
      if (!tok.next(type)) in.fail("expected 'property <type> <name>'");
      if (type == "list") {
        std::string_view count_type;
        if (!tok.next(count_type) || !tok.next(type)) in.fail("expected 'property list <count type> <type> <name>'");
        if (!type_from_name(count_type, p.count_type)) in.fail("unknown PLY type " + quoted(count_type));
        if (!is_integer(p.count_type)) in.fail("the length type of a list must be an integer type, got " + quoted(count_type));
        p.is_list = true;
      }
      if (!type_from_name(type, p.type)) in.fail("unknown PLY type " + quoted(type));
      if (!tok.next(name)) in.fail("property without a name");
      p.name = std::string(name);
      h.elements.back().properties.push_back(std::move(p));
    } else {
      in.fail("unexpected PLY header line starting with " + quoted(word));
    }
  }
  if (!have_format) throw FileError(path, "PLY header has no 'format' line");
  h.body_offset = in.end_offset();
  h.end_header_line = in.number();
  return h;
}

// Which element and properties hold the data we extract.
struct Layout {
  int vertex_element = -1;
  std::vector<int> vertex_slot;  ///< per vertex property: 0-2 position, 3-5 normal, -1 unused
  bool has_normals = false;
  int face_element = -1;
  int face_property = -1;
  std::uint64_t vertex_count = 0;
};

Layout find_layout(const std::string& path, const Header& h) {
  Layout l;
  for (std::size_t e = 0; e < h.elements.size(); ++e) {
    const Element& el = h.elements[e];
    if (el.name == "vertex" && l.vertex_element < 0) {
      l.vertex_element = static_cast<int>(e);
      l.vertex_count = el.count;
      if (el.count > static_cast<std::uint64_t>(std::numeric_limits<int>::max()))
        throw FileError(path, "too many vertices (" + std::to_string(el.count) + ")", el.line);
      l.vertex_slot.assign(el.properties.size(), -1);
      static const char* names[6] = {"x", "y", "z", "nx", "ny", "nz"};
      int found[6] = {-1, -1, -1, -1, -1, -1};
      for (std::size_t k = 0; k < el.properties.size(); ++k)
        for (int s = 0; s < 6; ++s)
          if (el.properties[k].name == names[s] && found[s] < 0) {
            if (el.properties[k].is_list)
              throw FileError(path, std::string("vertex property '") + names[s] + "' must be a scalar, not a list", el.line);
            found[s] = static_cast<int>(k);
          }
      for (int s = 0; s < 3; ++s) {
        if (found[s] < 0 && el.count > 0)
          throw FileError(path, std::string("the vertex element has no property '") + names[s] + "'", el.line);
        if (found[s] >= 0) l.vertex_slot[found[s]] = s;
      }
      l.has_normals = found[3] >= 0 && found[4] >= 0 && found[5] >= 0;
      if (l.has_normals)
        for (int s = 3; s < 6; ++s) l.vertex_slot[found[s]] = s;
    } else if (el.name == "face" && l.face_element < 0) {
      l.face_element = static_cast<int>(e);
      for (std::size_t k = 0; k < el.properties.size(); ++k) {
        const Property& p = el.properties[k];
        if (p.name != "vertex_indices" && p.name != "vertex_index") continue;
        if (!p.is_list) throw FileError(path, "face property '" + p.name + "' must be a list", el.line);
        if (!is_integer(p.type))
          throw FileError(path, "face property '" + p.name + "' must hold integers, not floating point", el.line);
        l.face_property = static_cast<int>(k);
        break;
      }
    }
  }
  return l;
}

// A hostile header may promise billions of elements: before allocating anything, check that the
// bytes after the header can hold at least the smallest possible encoding of every element.
void check_counts_fit(const std::string& path, const Header& h, std::size_t available) {
  unsigned __int128 needed = 0;
  for (const Element& el : h.elements) {
    std::uint64_t per_element = 0;
    for (const Property& p : el.properties) {
      if (h.encoding == Encoding::ascii) per_element += 2;  // one character and one separator
      else per_element += size_of(p.is_list ? p.count_type : p.type);
    }
    needed += static_cast<unsigned __int128>(per_element) * el.count;
    // The last ascii value may lack a trailing separator.
    const unsigned __int128 slack = h.encoding == Encoding::ascii ? 1 : 0;
    if (needed > available + slack) {
      throw FileError(path,
                      "header promises " + std::to_string(el.count) + " '" + el.name + "' elements of at least " +
                          std::to_string(per_element) + " bytes each, but only " + std::to_string(available) +
                          " bytes follow the header (truncated file or wrong count?)",
                      el.line);
    }
  }
}

// Appends the fan triangulation of polygon `corners` (already range-checked).
void add_fan(std::vector<Face>& faces, const std::vector<int>& corners) {
  for (std::size_t j = 1; j + 1 < corners.size(); ++j) faces.push_back({corners[0], corners[j], corners[j + 1]});
}

std::string element_label(const Element& el, std::uint64_t i) {
  return el.name + " " + std::to_string(i) + " (of " + std::to_string(el.count) + ")";
}

// ---- binary body ---------------------------------------------------------------------------------

class BinaryBody {
 public:
  BinaryBody(const std::string& path, std::string_view text, std::size_t offset, bool big_endian)
      : path_(path), begin_(text.data()), p_(text.data() + offset), end_(text.data() + text.size()),
        swap_(big_endian != host_is_big_endian()) {}

  std::size_t left() const { return static_cast<std::size_t>(end_ - p_); }
  void skip(std::size_t n) { p_ += n; }

  // The caller has checked left() >= size_of(t).
  double read_double(Type t) {
    switch (t) {
      case Type::int8: return read<std::int8_t>();
      case Type::uint8: return read<std::uint8_t>();
      case Type::int16: return read<std::int16_t>();
      case Type::uint16: return read<std::uint16_t>();
      case Type::int32: return read<std::int32_t>();
      case Type::uint32: return read<std::uint32_t>();
      case Type::float32: return read<float>();
      case Type::float64: return read<double>();
    }
    return 0.0;
  }
  long long read_integer(Type t) {
    switch (t) {
      case Type::int8: return read<std::int8_t>();
      case Type::uint8: return read<std::uint8_t>();
      case Type::int16: return read<std::int16_t>();
      case Type::uint16: return read<std::uint16_t>();
      case Type::int32: return read<std::int32_t>();
      case Type::uint32: return read<std::uint32_t>();
      default: return static_cast<long long>(read_double(t));  // excluded by find_layout
    }
  }

  [[noreturn]] void fail(const Element& el, std::uint64_t i, const std::string& problem) const {
    throw FileError(path_, element_label(el, i) + " at byte " + std::to_string(p_ - begin_) + ": " + problem);
  }
  [[noreturn]] void truncated(const Element& el, std::uint64_t i) const {
    fail(el, i, "truncated binary data (the file ends inside this element)");
  }

 private:
  static bool host_is_big_endian() { return __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__; }

  template <class T>
  T read() {
    unsigned char b[sizeof(T)];
    std::memcpy(b, p_, sizeof(T));
    p_ += sizeof(T);
    if (swap_)
      for (std::size_t k = 0; k < sizeof(T) / 2; ++k) std::swap(b[k], b[sizeof(T) - 1 - k]);
    T v;
    std::memcpy(&v, b, sizeof(T));
    return v;
  }

  const std::string& path_;
  const char* begin_;
  const char* p_;
  const char* end_;
  bool swap_;
};

void read_binary_body(const std::string& path, std::string_view text, const Header& h, const Layout& l,
                      TriangleMesh& mesh) {
  BinaryBody in(path, text, h.body_offset, h.encoding == Encoding::binary_big_endian);
  std::vector<int> corners;
  for (std::size_t e = 0; e < h.elements.size(); ++e) {
    const Element& el = h.elements[e];
    if (el.properties.empty()) continue;  // occupies no bytes, whatever its count
    const bool is_vertex = static_cast<int>(e) == l.vertex_element;
    const bool is_face = static_cast<int>(e) == l.face_element;
    bool all_scalar = true;
    std::size_t fixed = 0;
    for (const Property& p : el.properties) {
      all_scalar = all_scalar && !p.is_list;
      fixed += size_of(p.is_list ? p.count_type : p.type);
    }
    for (std::uint64_t i = 0; i < el.count; ++i) {
      if (in.left() < fixed) in.truncated(el, i);
      double v[6] = {0, 0, 0, 0, 0, 0};
      for (std::size_t k = 0; k < el.properties.size(); ++k) {
        const Property& p = el.properties[k];
        if (!p.is_list) {
          if (!all_scalar && in.left() < size_of(p.type)) in.truncated(el, i);
          const int slot = is_vertex ? l.vertex_slot[k] : -1;
          if (slot >= 0) v[slot] = in.read_double(p.type);
          else in.skip(size_of(p.type));
          continue;
        }
        if (in.left() < size_of(p.count_type)) in.truncated(el, i);
        const long long n = in.read_integer(p.count_type);
        if (n < 0) in.fail(el, i, "negative list length " + std::to_string(n));
        const std::size_t item = size_of(p.type);
        if (static_cast<unsigned long long>(n) > in.left() / item) in.truncated(el, i);
        if (!(is_face && static_cast<int>(k) == l.face_property)) {
          in.skip(static_cast<std::size_t>(n) * item);
          continue;
        }
        if (n < 3) in.fail(el, i, "a face needs at least 3 vertex indices, got " + std::to_string(n));
        corners.clear();
        for (long long c = 0; c < n; ++c) {
          const long long idx = in.read_integer(p.type);
          if (idx < 0 || static_cast<unsigned long long>(idx) >= l.vertex_count)
            in.fail(el, i, "vertex index " + std::to_string(idx) + " out of range (the file has " +
                               std::to_string(l.vertex_count) + " vertices)");
          corners.push_back(static_cast<int>(idx));
        }
        add_fan(mesh.faces, corners);
      }
      if (is_vertex) {
        for (int s = 0; s < (l.has_normals ? 6 : 3); ++s)
          if (!std::isfinite(v[s])) in.fail(el, i, "NaN or infinite coordinate");
        mesh.vertices.emplace_back(v[0], v[1], v[2]);
        if (l.has_normals) mesh.normals.emplace_back(v[3], v[4], v[5]);
      }
    }
  }
}

// ---- ascii body ----------------------------------------------------------------------------------

class AsciiBody {
 public:
  AsciiBody(const std::string& path, std::string_view text, const Header& h)
      : in_(path, text, h.body_offset, h.end_header_line), tokens_(std::string_view()) {}

  std::string_view next(const Element& el, std::uint64_t i) {
    std::string_view t;
    while (!tokens_.next(t)) {
      if (!in_.next()) in_.fail("the file ends inside " + element_label(el, i));
      tokens_ = Tokens(in_.line());
    }
    return t;
  }
  const LineReader& at() const { return in_; }
  [[noreturn]] void fail(const Element& el, std::uint64_t i, const std::string& problem) const {
    in_.fail(element_label(el, i) + ": " + problem);
  }
  // Anything but whitespace after the last element means the header's counts are wrong.
  void expect_end() {
    std::string_view t;
    for (;;) {
      if (tokens_.next(t)) in_.fail("unexpected data after the last element: " + quoted(t));
      if (!in_.next()) return;
      tokens_ = Tokens(in_.line());
    }
  }

 private:
  LineReader in_;
  Tokens tokens_;
};

void read_ascii_body(const std::string& path, std::string_view text, const Header& h, const Layout& l,
                     TriangleMesh& mesh) {
  AsciiBody in(path, text, h);
  std::vector<int> corners;
  for (std::size_t e = 0; e < h.elements.size(); ++e) {
    const Element& el = h.elements[e];
    if (el.properties.empty()) continue;
    const bool is_vertex = static_cast<int>(e) == l.vertex_element;
    const bool is_face = static_cast<int>(e) == l.face_element;
    for (std::uint64_t i = 0; i < el.count; ++i) {
      double v[6] = {0, 0, 0, 0, 0, 0};
      for (std::size_t k = 0; k < el.properties.size(); ++k) {
        const Property& p = el.properties[k];
        const std::string_view token = in.next(el, i);
        if (!p.is_list) {
          const int slot = is_vertex ? l.vertex_slot[k] : -1;
          if (slot >= 0) v[slot] = parse_double(in.at(), token, p.name.c_str());
          continue;
        }
        const long long n = parse_integer(in.at(), token, "a list length");
        if (n < 0) in.fail(el, i, "negative list length " + std::to_string(n));
        const bool wanted = is_face && static_cast<int>(k) == l.face_property;
        if (wanted && n < 3) in.fail(el, i, "a face needs at least 3 vertex indices, got " + std::to_string(n));
        corners.clear();
        for (long long c = 0; c < n; ++c) {  // bounded: each entry consumes a token of the file
          const std::string_view item = in.next(el, i);
          if (!wanted) continue;
          const long long idx = parse_integer(in.at(), item, "a vertex index");
          if (idx < 0 || static_cast<unsigned long long>(idx) >= l.vertex_count)
            in.fail(el, i, "vertex index " + std::to_string(idx) + " out of range (the file has " +
                               std::to_string(l.vertex_count) + " vertices)");
          corners.push_back(static_cast<int>(idx));
        }
        if (wanted) add_fan(mesh.faces, corners);
      }
      if (is_vertex) {
        mesh.vertices.emplace_back(v[0], v[1], v[2]);
        if (l.has_normals) mesh.normals.emplace_back(v[3], v[4], v[5]);
      }
    }
  }
  in.expect_end();
}

}  // namespace

TriangleMesh read_ply(const std::string& path, std::string_view text) {
  const Header h = parse_header(path, text);
  const Layout l = find_layout(path, h);
  check_counts_fit(path, h, text.size() - h.body_offset);
  TriangleMesh mesh;
  // Bounded by the file size through check_counts_fit.
  mesh.vertices.reserve(l.vertex_count);
  if (l.has_normals) mesh.normals.reserve(l.vertex_count);
  if (l.face_element >= 0 && l.face_property >= 0) mesh.faces.reserve(h.elements[l.face_element].count);
  if (h.encoding == Encoding::ascii) read_ascii_body(path, text, h, l, mesh);
  else read_binary_body(path, text, h, l, mesh);
  return mesh;
}

// ---- writer --------------------------------------------------------------------------------------

namespace {

template <class T>
void put_le(std::string& out, T v) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (__BYTE_ORDER__ == __ORDER_BIG_ENDIAN__)
    for (std::size_t k = 0; k < sizeof(T) / 2; ++k) std::swap(b[k], b[sizeof(T) - 1 - k]);
  out.append(reinterpret_cast<const char*>(b), sizeof(T));
}

}  // namespace

void write_ply(const std::string& path, const std::vector<Vec3>& vertices, const std::vector<Vec3>& normals,
               const std::vector<Face>& faces, bool binary) {
  write_file_atomically(path, [&](std::ostream& out) {
    std::string buf;
    buf += "ply\nformat ";
    buf += binary ? "binary_little_endian" : "ascii";
    buf += " 1.0\ncomment written by dtsl\nelement vertex " + std::to_string(vertices.size()) +
           "\nproperty double x\nproperty double y\nproperty double z\n";
    if (!normals.empty()) buf += "property double nx\nproperty double ny\nproperty double nz\n";
    if (!faces.empty())
      buf += "element face " + std::to_string(faces.size()) + "\nproperty list uchar int vertex_indices\n";
    buf += "end_header\n";
    // Doubles, not floats: reading a written file gives back exactly the same coordinates.
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      const int nvalues = normals.empty() ? 3 : 6;
      for (int c = 0; c < nvalues; ++c) {
        const double x = c < 3 ? vertices[i][c] : normals[i][c - 3];
        if (binary) {
          put_le(buf, x);
        } else {
          if (c > 0) buf += ' ';
          append_number(buf, x);
        }
      }
      if (!binary) buf += '\n';
      flush_if_large(out, buf);
    }
    for (const Face& f : faces) {
      if (binary) {
        put_le(buf, std::uint8_t{3});
        for (int c = 0; c < 3; ++c) put_le(buf, std::int32_t{f[c]});
      } else {
        buf += '3';
        for (int c = 0; c < 3; ++c) {
          buf += ' ';
          append_number(buf, static_cast<long long>(f[c]));
        }
        buf += '\n';
      }
      flush_if_large(out, buf);
    }
    flush_if_large(out, buf, true);
  });
}

}  // namespace dtsl::io_detail
