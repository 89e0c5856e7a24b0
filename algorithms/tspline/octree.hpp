// The T-mesh of the paper's §2.1: an octree over the domain cube, split where the data are dense
// ("the T-spline control grid (or T-mesh) is generated according to the distribution of data points
// through the octree subdivision"), 2:1 balanced, with O(1) point location. docs/design.md §1.
//
// Every cell is addressed by integers at the finest level (max_depth): the domain has
// R = 2^max_depth finest cells per axis, a cell of level l has side 2^(max_depth - l) in those units
// and its origin on that lattice. Vertices, knots and cell faces are exact integers, so the T-mesh's
// combinatorics (hanging vertices, knot rays, support overlaps) never depend on rounding.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "framework/config/options.hpp"
#include "framework/core/types.hpp"

namespace dtsl {

using Int3 = std::array<int, 3>;

/// Which neighbours 2:1 balance constrains: cells sharing a face (docs/design.md §1), or also those
/// sharing only an edge, or also those sharing only a vertex.
enum class Balance { face, edge, vertex };
Balance balance_from_string(const std::string& name);  // ConfigError for an unknown name
const char* to_string(Balance b);

/// How the T-mesh is made from the data points (docs/design.md §1).
///
/// Defaults (ours): points_per_cell = 64 puts the control point count in the paper's range (Table 1:
/// n_t = 870-2550 for 6k-26k points; the counts: docs/design.md §8). min_depth = 3 (cells of 0.31 with
/// the default margin) keeps the empty space the evolving front crosses from being spanned by a handful
/// of blending functions. Face balance is the docs/design.md rule; 'vertex' makes the T-mesh more
/// regular at more control points, 'edge' lies between: all three give a C2 rational T-spline with a
/// positive denominator. check() throws ConfigError naming the field (max_depth in [1, kMaxOctreeDepth],
/// min_depth in [0, kMaxOctreeDepth], margin in [0, 10]).
struct TMeshOptions final : Options {
  int max_depth = 6;          // finest level; the paper never goes beyond 6
  int min_depth = 3;          // every cell is split at least to this level (capped at max_depth)
  int points_per_cell = 64;   // split a cell holding more data points than this
  double margin = 0.25;       // domain = [-1-margin, 1+margin]^3 around the normalised data
  std::string balance = "face";

  void visit(FieldVisitor& v) override {
    v.field("max_depth", max_depth, "finest octree level; cells per axis there = 2^max_depth (paper: <= 6)");
    v.field("min_depth", min_depth, "coarsest level anywhere: cells are split to it even without data (capped at max_depth)");
    v.field("points_per_cell", points_per_cell, "a cell holding more data points than this is split");
    v.field("margin", margin, "the domain is [-1-margin, 1+margin]^3 in the normalised frame");
    v.field("balance", balance,
            "2:1 balance between neighbours sharing a 'face', an 'edge' (and faces) or a 'vertex' (all)");
  }
  void check() const override;
};

/// Largest max_depth accepted: 2^10 cells per axis keeps every lattice coordinate, vertex key and
/// Morton code in machine integers; a full octree that deep would not fit in memory anyway.
constexpr int kMaxOctreeDepth = 10;

class Octree {
 public:
  struct Cell {
    Int3 origin;          // lowest corner, in finest-level units
    int level;            // 0 = the whole domain
    int first_child = -1; // children are first_child + (bx | by << 1 | bz << 2); -1 for a leaf
  };

  /// A single leaf covering [domain_min, domain_min + side]^3 (side > 0, max_depth in [0, 10]).
  Octree(const Vec3& domain_min, double side, int max_depth);

  int max_depth() const { return max_depth_; }
  /// Finest-level cells per axis: the lattice is 0..resolution().
  int resolution() const { return 1 << max_depth_; }
  const Vec3& domain_min() const { return domain_min_; }
  double side() const { return side_; }
  BoundingBox domain() const;
  /// Side of a finest-level cell, in world units.
  double unit() const { return side_ / resolution(); }

  const std::vector<Cell>& cells() const { return cells_; }
  /// Side of a cell of level `level`, in finest-level units.
  int cell_size(int level) const { return 1 << (max_depth_ - level); }

  /// The leaves, as indices into cells(), in depth-first order (children in octant order). Leaf
  /// numbers (positions in this list) are what locate() returns.
  const std::vector<int>& leaves() const { return leaves_; }
  int leaf_count() const { return int(leaves_.size()); }
  const Cell& leaf(int leaf_number) const { return cells_[leaves_[leaf_number]]; }
  BoundingBox leaf_box(int leaf_number) const;
  double leaf_side(int leaf_number) const { return unit() * cell_size(leaf(leaf_number).level); }
  /// The deepest level any leaf reaches.
  int finest_leaf_level() const;

  /// The leaf holding the finest-level cell `c` (each coordinate in [0, resolution())): O(1) through
  /// a lookup table for max_depth <= 7, a short descent below that.
  int leaf_at(const Int3& c) const;
  /// The leaf holding x; points outside the domain are clamped onto it.
  int locate(const Vec3& x) const;

  /// World position of a lattice point (finest-level units; may lie outside the domain, for knots).
  Vec3 point(const Int3& lattice) const;
  double coordinate(int axis, double lattice) const { return domain_min_[axis] + lattice * unit(); }

  // --- construction (the builders below use these; a finished Octree is only read) ---
  /// Splits a leaf of level < max_depth into eight; the leaf list and lookup table are stale until
  /// finalize().
  void split(int cell);
  /// The cell (leaf or not, found by descending from the root) that holds finest-level cell `c` and
  /// has no children. Works at any time, unlike leaf_at().
  int descend(const Int3& c) const;
  /// Enforces 2:1 balance of the given kind by splitting too-coarse neighbours (ripple propagation).
  void balance(Balance kind);
  /// Rebuilds the leaf list and the lookup table.
  void finalize();
  /// False between a split() and the next finalize(): leaves(), leaf_at() and locate() are stale then.
  bool finalized() const { return finalized_; }

 private:
  Vec3 domain_min_;
  double side_;
  int max_depth_;
  std::vector<Cell> cells_;
  std::vector<int> leaves_;
  std::vector<int> leaf_number_;  // per cell: its leaf number, -1 for inner cells
  // Lookup table over the cells of level index_level_: a leaf number (>= 0) for a leaf at that level
  // or coarser, -(cell + 1) for a split cell of that level (descend from it).
  int index_level_ = 0;
  std::vector<std::int32_t> index_;
  bool finalized_ = false;
};

/// The T-mesh for `points` (already in the [-1,1]^3 frame): split while a cell holds more than
/// points_per_cell points (or is above min_depth) and is above max_depth, then balance. Throws
/// ConfigError for bad options; AlgorithmError for fewer than 4 points, all points coinciding, a
/// non-finite coordinate or a point outside the domain. Points all on a plane or a line are accepted: the mesh is refined along them only (tested).
Octree build_octree(const std::vector<Vec3>& points, const TMeshOptions& options);

/// The full octree of the given depth over [-1-margin, 1+margin]^3: the uniform tensor-product grid
/// (tests; the method builds its T-mesh from the data). ConfigError for a depth outside
/// [0, kMaxOctreeDepth] or a margin outside [0, 10].
Octree uniform_octree(int depth, double margin);

/// Splits the given leaves (leaf numbers of `octree`; those already at max_depth are left alone),
/// rebalances and returns the new T-mesh (for the final refinement, docs/design.md §1).
Octree refine_octree(const Octree& octree, const std::vector<int>& leaves_to_split, Balance balance);

/// Rebuilds an octree from its leaves (level and origin in finest-level units), as stored in a file.
/// AlgorithmError if the leaves overlap, leave a gap or do not lie on the octree's lattice.
struct LeafRecord {
  int level;
  Int3 origin;
};
Octree octree_from_leaves(const Vec3& domain_min, double side, int max_depth,
                          const std::vector<LeafRecord>& leaves);

/// True if no two leaves that are neighbours of the given kind differ by more than one level.
bool is_balanced(const Octree& octree, Balance kind);

}  // namespace dtsl
