#include "algorithms/tspline/octree.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "framework/core/error.hpp"

namespace dtsl {

namespace {

/// The table of locate() covers level min(max_depth, 7): 2^21 entries (8 MB) at most.
constexpr int kIndexLevel = 7;

std::string format_point(const Vec3& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

/// Neighbour directions for 2:1 balance: the 6 face, 12 edge and 8 vertex offsets.
std::vector<Int3> neighbour_directions(Balance kind) {
  std::vector<Int3> dirs;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int nonzero = std::abs(dx) + std::abs(dy) + std::abs(dz);
        if (nonzero == 0) continue;
        if (nonzero == 1 || (nonzero == 2 && kind != Balance::face) || (nonzero == 3 && kind == Balance::vertex))
          dirs.push_back({dx, dy, dz});
      }
  return dirs;
}

/// The finest-level cell just across the neighbour direction `d` from a cell (origin o, side s), or
/// false if that lies outside the domain. Any finest cell of the neighbouring block of side s will
/// do: a neighbour leaf coarser than the cell covers that whole block (cells are lattice-aligned).
bool neighbour_probe(const Int3& o, int s, const Int3& d, int resolution, Int3& probe) {
  for (int a = 0; a < 3; ++a) {
    probe[a] = d[a] < 0 ? o[a] - 1 : d[a] > 0 ? o[a] + s : o[a];
    if (probe[a] < 0 || probe[a] >= resolution) return false;
  }
  return true;
}

}  // namespace

Balance balance_from_string(const std::string& name) {
  if (name == "face") return Balance::face;
  if (name == "edge") return Balance::edge;
  if (name == "vertex") return Balance::vertex;
  throw ConfigError("balance: must be one of {face, edge, vertex}, got '" + name + "'");
}

const char* to_string(Balance b) {
  switch (b) {
    case Balance::face: return "face";
    case Balance::edge: return "edge";
    case Balance::vertex: return "vertex";
  }
  return "?";
}

void TMeshOptions::check() const {
  check_range("max_depth", max_depth, 1, kMaxOctreeDepth);
  check_range("min_depth", min_depth, 0, kMaxOctreeDepth);
  check_range("points_per_cell", points_per_cell, 1, 1 << 30);
  check_range("margin", margin, 0.0, 10.0);
  check_one_of("balance", balance, {"face", "edge", "vertex"});
}

// ---------------------------------------------------------------------------------------------------

Octree::Octree(const Vec3& domain_min, double side, int max_depth)
    : domain_min_(domain_min), side_(side), max_depth_(max_depth) {
  if (!(side > 0.0) || !std::isfinite(side) || !domain_min.allFinite())
    throw AlgorithmError("octree: the domain must be a finite cube of positive side");
  if (max_depth < 0 || max_depth > kMaxOctreeDepth)
    throw AlgorithmError("octree: max_depth must be in [0, " + std::to_string(kMaxOctreeDepth) + "], got " +
                         std::to_string(max_depth));
  cells_.push_back(Cell{{0, 0, 0}, 0, -1});
  finalize();
}

BoundingBox Octree::domain() const {
  BoundingBox b;
  b.min = domain_min_;
  b.max = domain_min_ + Vec3::Constant(side_);
  return b;
}

BoundingBox Octree::leaf_box(int leaf_number) const {
  const Cell& c = leaf(leaf_number);
  BoundingBox b;
  b.min = point(c.origin);
  const int s = cell_size(c.level);
  b.max = point({c.origin[0] + s, c.origin[1] + s, c.origin[2] + s});
  return b;
}

int Octree::finest_leaf_level() const {
  int l = 0;
  for (int leaf : leaves_) l = std::max(l, cells_[leaf].level);
  return l;
}

Vec3 Octree::point(const Int3& p) const {
  return domain_min_ + unit() * Vec3(p[0], p[1], p[2]);
}

void Octree::split(int cell) {
  if (cells_[cell].first_child >= 0) throw AlgorithmError("octree: split of a cell that is not a leaf");
  if (cells_[cell].level >= max_depth_) throw AlgorithmError("octree: split below max_depth");
  const Cell parent = cells_[cell];
  const int half = cell_size(parent.level + 1);
  cells_[cell].first_child = int(cells_.size());
  finalized_ = false;
  for (int o = 0; o < 8; ++o) {
    const Int3 origin{parent.origin[0] + ((o & 1) ? half : 0), parent.origin[1] + ((o & 2) ? half : 0),
                      parent.origin[2] + ((o & 4) ? half : 0)};
    cells_.push_back(Cell{origin, parent.level + 1, -1});
  }
}

int Octree::descend(const Int3& c) const {
  int cell = 0;
  while (cells_[cell].first_child >= 0) {
    const int bit = max_depth_ - cells_[cell].level - 1;
    const int octant = ((c[0] >> bit) & 1) | (((c[1] >> bit) & 1) << 1) | (((c[2] >> bit) & 1) << 2);
    cell = cells_[cell].first_child + octant;
  }
  return cell;
}

void Octree::balance(Balance kind) {
  // Leaves processed from the finest level to the coarsest: a leaf of level l forces every neighbour
  // (of the chosen kind) to level >= l - 1; the leaves this creates are of level <= l - 1 and so are
  // handled in a later pass. One sweep therefore balances the whole tree.
  const std::vector<Int3> dirs = neighbour_directions(kind);
  std::vector<std::vector<int>> by_level(max_depth_ + 1);
  for (int c = 0; c < int(cells_.size()); ++c)
    if (cells_[c].first_child < 0) by_level[cells_[c].level].push_back(c);
  const int R = resolution();
  for (int l = max_depth_; l >= 2; --l) {
    for (std::size_t k = 0; k < by_level[l].size(); ++k) {
      const int cell = by_level[l][k];
      if (cells_[cell].first_child >= 0) continue;  // split since it was listed
      const Int3 origin = cells_[cell].origin;
      for (const Int3& d : dirs) {
        Int3 probe;
        if (!neighbour_probe(origin, cell_size(l), d, R, probe)) continue;
        for (int n = descend(probe); cells_[n].level < l - 1; n = descend(probe)) {
          split(n);
          const int first = cells_[n].first_child;
          for (int o = 0; o < 8; ++o) by_level[cells_[n].level + 1].push_back(first + o);
        }
      }
    }
  }
}

void Octree::finalize() {
  leaves_.clear();
  leaf_number_.assign(cells_.size(), -1);
  // Depth-first, children in octant order: deterministic leaf (and so control point) numbering.
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const int c = stack.back();
    stack.pop_back();
    if (cells_[c].first_child < 0) {
      leaf_number_[c] = int(leaves_.size());
      leaves_.push_back(c);
    } else {
      for (int o = 7; o >= 0; --o) stack.push_back(cells_[c].first_child + o);
    }
  }
  index_level_ = std::min(max_depth_, kIndexLevel);
  const int n = 1 << index_level_;
  index_.assign(std::size_t(n) * n * n, 0);
  const int shift = max_depth_ - index_level_;
  stack.assign(1, 0);
  while (!stack.empty()) {
    const int c = stack.back();
    stack.pop_back();
    const Cell& cell = cells_[c];
    if (cell.first_child >= 0 && cell.level < index_level_) {
      for (int o = 0; o < 8; ++o) stack.push_back(cell.first_child + o);
      continue;
    }
    // A leaf at index_level_ or coarser fills its block; a split cell at index_level_ its one entry.
    const std::int32_t entry = cell.first_child < 0 ? leaf_number_[c] : -(c + 1);
    const int block = 1 << (index_level_ - std::min(cell.level, index_level_));
    const Int3 o{cell.origin[0] >> shift, cell.origin[1] >> shift, cell.origin[2] >> shift};
    for (int z = 0; z < block; ++z)
      for (int y = 0; y < block; ++y)
        for (int x = 0; x < block; ++x)
          index_[(std::size_t(o[2] + z) * n + (o[1] + y)) * n + (o[0] + x)] = entry;
  }
  finalized_ = true;
}

int Octree::leaf_at(const Int3& c) const {
  const int shift = max_depth_ - index_level_;
  const int n = 1 << index_level_;
  const std::int32_t e =
      index_[(std::size_t(c[2] >> shift) * n + (c[1] >> shift)) * n + (c[0] >> shift)];
  if (e >= 0) return e;
  int cell = -e - 1;
  while (cells_[cell].first_child >= 0) {
    const int bit = max_depth_ - cells_[cell].level - 1;
    const int octant = ((c[0] >> bit) & 1) | (((c[1] >> bit) & 1) << 1) | (((c[2] >> bit) & 1) << 2);
    cell = cells_[cell].first_child + octant;
  }
  return leaf_number_[cell];
}

int Octree::locate(const Vec3& x) const {
  const int R = resolution();
  const double inv = R / side_;
  Int3 c;
  for (int a = 0; a < 3; ++a) {
    const double s = (x[a] - domain_min_[a]) * inv;
    c[a] = s >= 0.0 ? (s < R ? int(s) : R - 1) : 0;  // NaN -> 0
  }
  return leaf_at(c);
}

// ---------------------------------------------------------------------------------------------------

namespace {

/// Morton code of a finest-level cell, root octant in the most significant bits, so that the points
/// of any octree cell form one contiguous run of the sorted codes.
std::uint32_t morton(const Int3& c, int depth) {
  std::uint32_t code = 0;
  for (int bit = depth - 1; bit >= 0; --bit)
    code = (code << 3) | std::uint32_t((c[0] >> bit) & 1) | (std::uint32_t((c[1] >> bit) & 1) << 1) |
           (std::uint32_t((c[2] >> bit) & 1) << 2);
  return code;
}

void check_points(const std::vector<Vec3>& points, const BoundingBox& domain) {
  if (points.size() < 4)
    throw AlgorithmError("T-mesh: needs at least 4 data points, got " + std::to_string(points.size()));
  const double slack = 1e-9 * (domain.max - domain.min).maxCoeff();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    if (!p.allFinite())
      throw AlgorithmError("T-mesh: point " + std::to_string(i) + " has a NaN or infinite coordinate");
    if ((p.array() < domain.min.array() - slack).any() || (p.array() > domain.max.array() + slack).any())
      throw AlgorithmError("T-mesh: point " + std::to_string(i) + " " + format_point(p) +
                           " lies outside the domain [" + std::to_string(domain.min.x()) + ", " +
                           std::to_string(domain.max.x()) +
                           "]^3; points must be normalised into [-1,1]^3 first");
  }
  const BoundingBox box = bounding_box(points);
  if (!(box.extent().maxCoeff() > 0.0))
    throw AlgorithmError("T-mesh: all " + std::to_string(points.size()) + " data points coincide at " +
                         format_point(points[0]) + "; no surface can be fitted");
}

}  // namespace

Octree uniform_octree(int depth, double margin) {
  if (depth < 0 || depth > kMaxOctreeDepth)
    throw ConfigError("max_depth: must be in [0, " + std::to_string(kMaxOctreeDepth) + "], got " +
                      std::to_string(depth));
  check_range("margin", margin, 0.0, 10.0);
  Octree tree(Vec3::Constant(-1.0 - margin), 2.0 + 2.0 * margin, depth);
  // Breadth-first: cells are appended level by level, so splitting in index order reaches every cell.
  for (int c = 0; c < int(tree.cells().size()); ++c)
    if (tree.cells()[c].level < depth) tree.split(c);
  tree.finalize();
  return tree;
}

Octree build_octree(const std::vector<Vec3>& points, const TMeshOptions& options) {
  options.check();
  const int depth = options.max_depth;
  Octree tree(Vec3::Constant(-1.0 - options.margin), 2.0 + 2.0 * options.margin, depth);
  check_points(points, tree.domain());

  const int R = tree.resolution();
  const double inv = R / tree.side();
  std::vector<std::uint32_t> codes(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    Int3 c;
    for (int a = 0; a < 3; ++a) c[a] = std::clamp(int(std::floor((points[i][a] - tree.domain_min()[a]) * inv)), 0, R - 1);
    codes[i] = morton(c, depth);
  }
  std::sort(codes.begin(), codes.end());

  // Split top-down; a cell's points are the codes in [begin, end), its children's the sub-runs with
  // the next three bits equal to the octant.
  struct Task {
    int cell;
    std::size_t begin, end;
  };
  std::vector<Task> tasks{{0, 0, codes.size()}};
  while (!tasks.empty()) {
    const Task t = tasks.back();
    tasks.pop_back();
    const int level = tree.cells()[t.cell].level;
    const bool crowded = t.end - t.begin > std::size_t(options.points_per_cell);
    if (level >= depth || !(crowded || level < options.min_depth)) continue;  // min_depth capped by depth
    tree.split(t.cell);
    const int first = tree.cells()[t.cell].first_child;
    const int shift = 3 * (depth - level - 1);
    std::size_t begin = t.begin;
    for (int o = 0; o < 8; ++o) {
      const std::size_t end = std::size_t(
          std::partition_point(codes.begin() + begin, codes.begin() + t.end,
                               [&](std::uint32_t code) { return int((code >> shift) & 7u) <= o; }) -
          codes.begin());
      tasks.push_back({first + o, begin, end});
      begin = end;
    }
  }
  tree.balance(balance_from_string(options.balance));
  tree.finalize();
  return tree;
}

Octree refine_octree(const Octree& octree, const std::vector<int>& leaves_to_split, Balance balance) {
  Octree tree = octree;
  for (int leaf : leaves_to_split) {
    if (leaf < 0 || leaf >= octree.leaf_count())
      throw AlgorithmError("refine_octree: leaf number " + std::to_string(leaf) + " out of range");
    const int cell = octree.leaves()[leaf];
    if (tree.cells()[cell].first_child < 0 && tree.cells()[cell].level < tree.max_depth()) tree.split(cell);
  }
  tree.balance(balance);
  tree.finalize();
  return tree;
}

Octree octree_from_leaves(const Vec3& domain_min, double side, int max_depth,
                          const std::vector<LeafRecord>& leaves) {
  Octree tree(domain_min, side, max_depth);
  const int R = tree.resolution();
  std::vector<char> declared;  // per cell: listed as a leaf
  for (std::size_t i = 0; i < leaves.size(); ++i) {
    const LeafRecord& r = leaves[i];
    const std::string which = "leaf " + std::to_string(i);
    if (r.level < 0 || r.level > max_depth)
      throw AlgorithmError(which + ": level " + std::to_string(r.level) + " outside [0, " +
                           std::to_string(max_depth) + "]");
    const int s = tree.cell_size(r.level);
    for (int a = 0; a < 3; ++a)
      if (r.origin[a] < 0 || r.origin[a] + s > R || r.origin[a] % s != 0)
        throw AlgorithmError(which + ": origin is not a lattice cell of its level inside the domain");
    int cell = tree.descend(r.origin);
    while (tree.cells()[cell].level < r.level) {
      if (cell < int(declared.size()) && declared[cell])
        throw AlgorithmError(which + " lies inside another declared leaf");
      tree.split(cell);
      cell = tree.descend(r.origin);
    }
    declared.resize(tree.cells().size(), 0);
    if (tree.cells()[cell].level != r.level || declared[cell])
      throw AlgorithmError(which + " overlaps another declared leaf");
    declared[cell] = 1;
  }
  declared.resize(tree.cells().size(), 0);
  for (int c = 0; c < int(tree.cells().size()); ++c)
    if (tree.cells()[c].first_child < 0 && !declared[c])
      throw AlgorithmError("the leaves leave a gap: the cell of level " + std::to_string(tree.cells()[c].level) +
                           " at lattice origin (" + std::to_string(tree.cells()[c].origin[0]) + ", " +
                           std::to_string(tree.cells()[c].origin[1]) + ", " +
                           std::to_string(tree.cells()[c].origin[2]) + ") is not covered");
  tree.finalize();
  return tree;
}

bool is_balanced(const Octree& octree, Balance kind) {
  const std::vector<Int3> dirs = neighbour_directions(kind);
  for (int leaf = 0; leaf < octree.leaf_count(); ++leaf) {
    const Octree::Cell& c = octree.leaf(leaf);
    for (const Int3& d : dirs) {
      Int3 probe;
      if (!neighbour_probe(c.origin, octree.cell_size(c.level), d, octree.resolution(), probe)) continue;
      if (octree.leaf(octree.leaf_at(probe)).level < c.level - 1) return false;
    }
  }
  return true;
}

}  // namespace dtsl
