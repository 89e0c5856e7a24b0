#include "algorithms/tspline/tspline_io.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "framework/core/atomic_file.hpp"
#include "framework/core/error.hpp"

namespace dtsl {

namespace {

constexpr const char* kMagic = "dtsl-tspline";
constexpr int kVersion = 1;

/// Line-by-line reader that skips blank and comment lines and names file and line in every error.
class RecordReader {
 public:
  explicit RecordReader(const std::string& path) : path_(path), in_(path) {
    if (!in_) throw FileError(path, std::string("cannot open for reading: ") + std::strerror(errno));
  }

  /// The tokens of the next record; FileError at the end of the file (`expected` says what was due).
  std::vector<std::string> next(const std::string& expected) {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_;
      std::istringstream s(line);
      std::vector<std::string> tokens;
      for (std::string t; s >> t;) tokens.push_back(t);
      if (tokens.empty() || tokens[0][0] == '#') continue;
      return tokens;
    }
    throw FileError(path_, "unexpected end of file, expected " + expected, line_);
  }

  /// The next record, which must be `keyword` followed by `count` values.
  std::vector<std::string> keyword(const char* keyword, std::size_t count) {
    std::vector<std::string> t = next(std::string("'") + keyword + "'");
    if (t[0] != keyword) fail(std::string("expected '") + keyword + "', got '" + t[0] + "'");
    if (t.size() != count + 1)
      fail(std::string("'") + keyword + "' takes " + std::to_string(count) + " value(s), got " +
           std::to_string(t.size() - 1));
    return t;
  }

  [[noreturn]] void fail(const std::string& problem) const { throw FileError(path_, problem, line_); }

  double to_double(const std::string& s) const {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v)) fail("not a finite number: '" + s + "'");
    return v;
  }

  long to_int(const std::string& s, long lo, long hi) const {
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(s.c_str(), &end, 10);
    if (s.empty() || *end != '\0' || errno == ERANGE) fail("not an integer: '" + s + "'");
    if (v < lo || v > hi)
      fail("value " + s + " outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return v;
  }

 private:
  std::string path_;
  std::ifstream in_;
  long line_ = 0;
};

}  // namespace

void save_tspline(const std::string& path, const TSpline& spline) {
  const Octree& tree = spline.tmesh();
  write_file_atomically(path, [&](std::ostream& out) {
    out << std::setprecision(17);
    out << kMagic << " " << kVersion << "\n";
    out << "# rational cubic T-spline level set (docs/design.md §1); lattice units = finest-level cells\n";
    out << "domain " << tree.domain_min().x() << " " << tree.domain_min().y() << " " << tree.domain_min().z()
        << " " << tree.side() << "\n";
    out << "max_depth " << tree.max_depth() << "\n";
    out << "leaves " << tree.leaf_count() << "\n";
    for (int l = 0; l < tree.leaf_count(); ++l) {
      const Octree::Cell& c = tree.leaf(l);
      out << c.level << " " << c.origin[0] << " " << c.origin[1] << " " << c.origin[2] << "\n";
    }
    out << "coefficients " << spline.coefficients().size() << "\n";
    for (double c : spline.coefficients()) out << c << "\n";
    out << "end\n";
  });
}

TSpline load_tspline(const std::string& path) {
  RecordReader r(path);
  const auto header = r.next("the header '" + std::string(kMagic) + " " + std::to_string(kVersion) + "'");
  if (header.size() != 2 || header[0] != kMagic) r.fail("not a dtsl T-spline file (expected '" + std::string(kMagic) + " <version>')");
  if (r.to_int(header[1], 0, 1 << 30) != kVersion) r.fail("unsupported version " + header[1]);

  const auto domain = r.keyword("domain", 4);
  const Vec3 domain_min(r.to_double(domain[1]), r.to_double(domain[2]), r.to_double(domain[3]));
  const double side = r.to_double(domain[4]);
  if (!(side > 0.0)) r.fail("domain side must be positive, got " + domain[4]);
  const int depth = int(r.to_int(r.keyword("max_depth", 1)[1], 0, kMaxOctreeDepth));
  const long max_leaves = 1L << (3 * depth);
  const long leaf_count = r.to_int(r.keyword("leaves", 1)[1], 1, max_leaves);
  std::vector<LeafRecord> leaves;
  leaves.reserve(std::size_t(std::min(leaf_count, 1L << 20)));  // a bogus count must not allocate
  const long lattice = 1L << depth;
  for (long l = 0; l < leaf_count; ++l) {
    const auto t = r.next("a leaf record '<level> <x> <y> <z>'");
    if (t.size() != 4) r.fail("a leaf record has 4 integers '<level> <x> <y> <z>', got " + std::to_string(t.size()) + " fields");
    LeafRecord leaf;
    leaf.level = int(r.to_int(t[0], 0, depth));
    for (int a = 0; a < 3; ++a) leaf.origin[a] = int(r.to_int(t[a + 1], 0, lattice - 1));
    leaves.push_back(leaf);
  }
  std::shared_ptr<TSplineBasis> basis;
  try {
    basis = std::make_shared<TSplineBasis>(octree_from_leaves(domain_min, side, depth, leaves));
  } catch (const AlgorithmError& e) {
    throw FileError(path, std::string("invalid T-mesh: ") + e.what());
  }
  const long n = r.to_int(r.keyword("coefficients", 1)[1], 0, 1L << 40);
  if (n != basis->size())
    r.fail("the T-mesh has " + std::to_string(basis->size()) + " control points but the file lists " +
           std::to_string(n) + " coefficients");
  std::vector<double> c(n);
  for (long i = 0; i < n; ++i) {
    const auto t = r.next("coefficient " + std::to_string(i));
    if (t.size() != 1) r.fail("a coefficient line holds one number");
    c[i] = r.to_double(t[0]);
  }
  r.keyword("end", 0);
  return TSpline(std::move(basis), std::move(c));
}

std::vector<std::array<Vec3, 2>> tmesh_edges(const Octree& octree) {
  // Each edge as a pair of lattice-vertex keys (smaller first), deduplicated.
  const std::uint64_t n = std::uint64_t(octree.resolution()) + 1;
  auto key = [n](const Int3& p) { return (std::uint64_t(p[2]) * n + std::uint64_t(p[1])) * n + std::uint64_t(p[0]); };
  std::vector<std::pair<std::uint64_t, std::uint64_t>> edges;
  edges.reserve(std::size_t(octree.leaf_count()) * 12);
  for (int l = 0; l < octree.leaf_count(); ++l) {
    const Octree::Cell& c = octree.leaf(l);
    const int s = octree.cell_size(c.level);
    for (int axis = 0; axis < 3; ++axis) {
      const int e = (axis + 1) % 3, f = (axis + 2) % 3;
      for (int k = 0; k < 4; ++k) {
        Int3 a = c.origin;
        a[e] += (k & 1) ? s : 0;
        a[f] += (k & 2) ? s : 0;
        Int3 b = a;
        b[axis] += s;
        edges.emplace_back(key(a), key(b));
      }
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  auto lattice = [n](std::uint64_t k) { return Int3{int(k % n), int(k / n % n), int(k / n / n)}; };
  std::vector<std::array<Vec3, 2>> out;
  out.reserve(edges.size());
  for (const auto& e : edges) out.push_back({octree.point(lattice(e.first)), octree.point(lattice(e.second))});
  return out;
}

void write_tmesh_obj(const std::string& path, const Octree& octree) {
  const auto edges = tmesh_edges(octree);
  // Shared vertices: number the distinct end points (exact lattice positions, so == is safe).
  std::vector<Vec3> points;
  points.reserve(2 * edges.size());
  for (const auto& e : edges) points.insert(points.end(), {e[0], e[1]});
  auto less = [](const Vec3& a, const Vec3& b) { return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3); };
  std::sort(points.begin(), points.end(), less);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  auto index = [&](const Vec3& p) { return std::lower_bound(points.begin(), points.end(), p, less) - points.begin() + 1; };
  write_file_atomically(path, [&](std::ostream& out) {
    out << std::setprecision(9);
    out << "# T-mesh: " << octree.leaf_count() << " leaf cells, " << edges.size() << " edges\n";
    for (const Vec3& p : points) out << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
    for (const auto& e : edges) out << "l " << index(e[0]) << " " << index(e[1]) << "\n";
  });
}

}  // namespace dtsl
