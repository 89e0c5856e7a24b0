#include "framework/pipeline/line_obj.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "framework/core/atomic_file.hpp"
#include "framework/core/error.hpp"

namespace dtsl {

namespace {

bool lexicographic_less(const Vec3& a, const Vec3& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

}  // namespace

void write_line_obj(const std::string& path, const std::vector<Segment>& segments, const std::string& comment) {
  for (std::size_t i = 0; i < segments.size(); ++i)
    if (!segments[i][0].allFinite() || !segments[i][1].allFinite())
      throw FileError(path, "cannot write segment " + std::to_string(i) + ": NaN or infinite coordinate");
  // Shared end points: cell edges meet at lattice points, so equal positions are exactly equal.
  std::vector<Vec3> points;
  points.reserve(2 * segments.size());
  for (const Segment& s : segments) points.insert(points.end(), {s[0], s[1]});
  std::sort(points.begin(), points.end(), lexicographic_less);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  auto index = [&](const Vec3& p) {
    return std::lower_bound(points.begin(), points.end(), p, lexicographic_less) - points.begin() + 1;
  };
  write_file_atomically(path, [&](std::ostream& out) {
    out.precision(17);  // reads back exactly
    if (!comment.empty()) out << "# " << comment << "\n";
    for (const Vec3& p : points) out << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
    for (const Segment& s : segments) out << "l " << index(s[0]) << " " << index(s[1]) << "\n";
  });
}

std::vector<Segment> read_line_obj(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path, "cannot open");
  std::vector<Vec3> vertices;
  std::vector<std::pair<long long, long>> ends;  // 0-based vertex index (checked at the end), line number
  std::vector<std::array<std::size_t, 2>> pairs;  // into `ends`
  std::string line;
  long number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (const std::size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream tok(line);
    std::string word;
    if (!(tok >> word)) continue;
    if (word == "v") {
      Vec3 p;
      for (int c = 0; c < 3; ++c) {
        std::string t;
        char* end = nullptr;
        if (!(tok >> t)) throw FileError(path, "a vertex needs 3 coordinates", number);
        p[c] = std::strtod(t.c_str(), &end);
        if (end != t.c_str() + t.size() || !std::isfinite(p[c]))
          throw FileError(path, "bad vertex coordinate '" + t + "'", number);
      }
      vertices.push_back(p);
    } else if (word == "l") {
      std::vector<long long> corners;
      for (std::string t; tok >> t;) {
        t = t.substr(0, t.find('/'));  // "v/vt": the texture index is not kept
        long long i = 0;
        const auto r = std::from_chars(t.data(), t.data() + t.size(), i);
        if (r.ec != std::errc() || r.ptr != t.data() + t.size() || i == 0)
          throw FileError(path, "bad line vertex index '" + t + "' (OBJ indices start at 1)", number);
        if (i < 0) {
          i += static_cast<long long>(vertices.size());
          if (i < 0) throw FileError(path, "relative line vertex index out of range", number);
        } else {
          --i;
        }
        corners.push_back(i);
      }
      if (corners.size() < 2) throw FileError(path, "a line needs at least 2 vertices", number);
      for (std::size_t k = 0; k < corners.size(); ++k) ends.emplace_back(corners[k], number);
      for (std::size_t k = 0; k + 1 < corners.size(); ++k)
        pairs.push_back({ends.size() - corners.size() + k, ends.size() - corners.size() + k + 1});
    }
  }
  if (in.bad()) throw FileError(path, "read error");
  // OBJ allows an index to name a vertex defined later in the file.
  for (const auto& [i, at] : ends)
    if (i >= static_cast<long long>(vertices.size()))
      throw FileError(path, "line vertex index " + std::to_string(i + 1) + " out of range (the file has " +
                                std::to_string(vertices.size()) + " vertices)", at);
  std::vector<Segment> segments;
  segments.reserve(pairs.size());
  for (const auto& p : pairs) segments.push_back({vertices[ends[p[0]].first], vertices[ends[p[1]].first]});
  return segments;
}

}  // namespace dtsl
