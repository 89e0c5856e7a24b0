// The blending functions of the T-spline on a T-mesh, B_i(x) = N[u_i](x) N[v_i](y) N[w_i](z), and
// their fast evaluation (paper §2.1: "we use an octree to store the information of associated T-spline
// control coefficients for any point"; docs/design.md §1). Independent of the coefficients, so one basis
// serves the level set, its time derivative c' and every least-squares row built on it.
//
// Evaluation of a point: O(1) leaf lookup, then only the control points whose support overlaps that
// leaf (its support list). Along each axis the support list of a leaf uses only a handful of distinct
// knot vectors (on the uniform grid: 4), so the univariate B-splines are evaluated once per distinct
// knot vector and the tensor products are formed from those — the same saving a tensor-product
// B-spline evaluation makes, kept on a T-mesh.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "algorithms/tspline/bspline.hpp"
#include "algorithms/tspline/knots.hpp"
#include "algorithms/tspline/octree.hpp"
#include "framework/core/implicit.hpp"

namespace dtsl {

/// The control points active at one point x, for least-squares assembly: the normalised basis
/// R_i = B_i / sum_j B_j (a partition of unity: f = sum_i c_i R_i), and its derivatives. Only the
/// functions with B_i(x) > 0 are listed (where B_i = 0 its gradient and Hessian vanish too, C2).
/// Reuse one object across calls: its vectors keep their capacity.
struct ActiveBasis {
  std::vector<int> index;       // control point indices
  std::vector<double> value;    // R_i(x)
  std::vector<Vec3> gradient;   // grad R_i(x)
  std::vector<Mat3> hessian;    // Hessian of R_i(x); filled only when asked for
  double denominator = 0.0;     // sum_j B_j(x) > 0
  int leaf = -1;                // the leaf holding x

  int size() const { return int(index.size()); }
};

class TSplineBasis {
 public:
  /// Control points, knots and support lists of the T-mesh `octree` (which must be finalized, as the
  /// builders in octree.hpp return it).
  explicit TSplineBasis(Octree octree);

  const Octree& octree() const { return octree_; }
  BoundingBox domain() const { return octree_.domain(); }

  /// Number of control points (= blending functions = coefficients).
  int size() const { return int(vertices_.size()); }
  /// Lattice position of control point i (finest-level units) and its world position.
  const Int3& vertex(int i) const { return vertices_[i]; }
  Vec3 control_point(int i) const { return octree_.point(vertices_[i]); }
  const LocalKnots& knots(int i) const { return knots_[i]; }
  /// The knots of B_i along `axis` in world coordinates.
  KnotValues knot_values(int i, int axis) const;
  /// The Greville point of B_i: per axis the mean of its three inner knots (docs/design.md §1).
  Vec3 greville(int i) const;
  std::vector<Vec3> greville_points() const;

  /// B_i(x) (unnormalised) and optionally its gradient and Hessian, straight from the Cox–de Boor
  /// recursion on B_i's knots: slow, independent of the support lists; for tests and figures.
  double blending(int i, const Vec3& x, Vec3* gradient = nullptr, Mat3* hessian = nullptr) const;

  /// f(x) = sum_i c_i B_i(x) / sum_i B_i(x) for coefficients c[0..size()), with gradient and Hessian
  /// by the quotient rule where the pointers are non-null. Points outside the domain are clamped onto
  /// it (f is extended as constant along the normal of the domain's faces). Thread-safe.
  double evaluate(const double* coefficients, const Vec3& x, Vec3* gradient = nullptr,
                  Mat3* hessian = nullptr) const;

  /// The functions active at x with R_i, grad R_i and (if `hessians`) the Hessian of R_i. Thread-safe
  /// with one ActiveBasis per thread.
  void active(const Vec3& x, ActiveBasis& out, bool hessians = false) const;

  /// Per leaf: 1 if every coefficient of its support list is positive. f = sum c_i B_i / sum B_i is
  /// a convex combination of them (B_i >= 0), so f > 0 everywhere in such a leaf.
  std::vector<char> positive_leaves(const double* coefficients) const;
  /// The leaf evaluate() uses for x (x clamped onto the domain as there).
  int leaf_of(const Vec3& x) const { return octree_.locate(clamp(x)); }

  /// The support list of a leaf: the control points whose (open) support box overlaps the leaf.
  std::vector<int> support(int leaf) const;
  int support_size(int leaf) const {
    return int(groups_[leaves_[leaf].group_end].entry_begin - groups_[leaves_[leaf].group_begin].entry_begin);
  }

  struct Stats {
    int control_points = 0, leaves = 0, distinct_knot_vectors = 0;
    int shapes = 0;             // distinct knot-interval patterns (B-splines up to translation)
    double mean_support = 0.0;  // mean support-list length over the leaves
    int max_support = 0;
    int max_local_splines = 0;  // most distinct knot vectors one leaf needs along one axis
    double mean_groups = 0.0;   // mean number of (y, z) knot-vector groups per leaf
  };
  Stats stats() const;

  /// Most distinct knot vectors along one axis a leaf may need (evaluation works on a stack buffer of
  /// this size; a 2:1-balanced T-mesh needs far fewer — the constructor checks).
  static constexpr int kMaxLocalSplines = 255;

 private:
  template <int Order>
  double evaluate_impl(const double* c, const Vec3& x, Vec3* gradient, Mat3* hessian) const;
  Vec3 clamp(const Vec3& x) const;

  // A leaf's support list is stored in groups of entries sharing their y and z knot vectors, so that
  // the y-z factor of B_i is formed once per group and the per-entry work is four additions (f and
  // grad f): sums over the group of N_x, c N_x, N_x', c N_x'. Equal y and z knot vectors mean equal y
  // and z vertex coordinates (the middle knot), i.e. one lattice row, and a row's vertices are
  // consecutive in the (z, y, x) control point order: so an entry needs only a small offset from its
  // group's first control index (4 bytes an entry keep the lists cache-friendly).
  struct SupportEntry {
    std::uint16_t offset;  // control index - group's control_base (< 2^10 + 1: one lattice row)
    std::uint8_t kx;       // which of the leaf's distinct x knot vectors B_i uses
  };
  struct SupportGroup {
    std::uint32_t entry_begin;  // the group ends where the next one begins (a sentinel closes the last)
    std::int32_t control_base;
    std::uint8_t ky, kz;        // the leaf's distinct y and z knot vectors shared by the group
  };
  struct LeafSupport {
    std::uint32_t group_begin = 0, group_end = 0;  // into groups_
    std::uint32_t entry_begin = 0;                 // = groups_[group_begin].entry_begin, kept here so
                                                   // groups, entries and splines load in parallel
    std::uint32_t spline_begin = 0;                // into leaf_splines_: count[0] + count[1] + count[2]
    std::uint8_t count[3] = {0, 0, 0};
  };
  /// Fills n[a][k] = (N, N', N'') (the first Order+1 of them) of the leaf's k-th distinct knot vector
  /// along axis a, at the clamped point x.
  template <int Order>
  void evaluate_splines(const LeafSupport& leaf, const Vec3& x, double (*n)[kMaxLocalSplines][3]) const;

  Octree octree_;
  std::vector<Int3> vertices_;
  std::vector<LocalKnots> knots_;
  // The univariate B-splines in lattice units, where knots are integers: a B-spline is a translate
  // N_shape(u - t0) of one of few knot-interval patterns (2:1 balance keeps the gaps powers of two).
  // The shape table is a few kB and stays in L1 cache however the queries jump around the domain;
  // derivatives come out per lattice unit and are scaled once per evaluation.
  struct LatticeSpline {
    std::int32_t t0;     // first knot, lattice units
    std::int32_t shape;  // into shapes_
  };
  std::vector<CubicBSpline> shapes_;       // knots (0, t1 - t0, ..., t4 - t0)
  std::vector<LatticeSpline> knot_vectors_;  // the distinct knot vectors (all axes share the table)
  std::vector<SupportEntry> entries_;
  std::vector<SupportGroup> groups_;  // with a sentinel at the end
  std::vector<LatticeSpline> leaf_splines_;
  std::vector<LeafSupport> leaves_;
};

}  // namespace dtsl
