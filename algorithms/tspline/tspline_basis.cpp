#include "algorithms/tspline/tspline_basis.hpp"

#include <algorithm>
#include <map>
#include <sstream>

#include "framework/core/error.hpp"

namespace dtsl {

TSplineBasis::TSplineBasis(Octree octree) : octree_(std::move(octree)) {
  if (!octree_.finalized()) throw AlgorithmError("T-spline: the octree was split but not finalized");
  vertices_ = control_vertices(octree_);
  const int n = size();
  knots_.resize(n);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) knots_[i] = local_knots(octree_, vertices_[i]);

  // Distinct knot vectors, each a translate of a shape (its knots minus the first). Simple knots are
  // guaranteed: every knot is a face strictly beyond the previous one.
  std::map<LatticeKnots, int> spline_id, shape_id;
  std::vector<std::array<int, 3>> spline_of(n);
  for (int i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      const LatticeKnots& k = knots_[i][a];
      auto [it, inserted] = spline_id.emplace(k, int(knot_vectors_.size()));
      if (inserted) {
        LatticeKnots relative;
        for (int j = 0; j < 5; ++j) relative[j] = k[j] - k[0];
        auto [shape, new_shape] = shape_id.emplace(relative, int(shapes_.size()));
        if (new_shape) {
          KnotValues t;
          for (int j = 0; j < 5; ++j) t[j] = relative[j];
          shapes_.emplace_back(t);
        }
        knot_vectors_.push_back({k[0], shape->second});
      }
      spline_of[i][a] = it->second;
    }
  }

  // Support lists: the leaves each control point's open support box overlaps, found by descending the
  // octree; counted in a first pass, filled in a second (entries sorted by control index per leaf).
  const auto& cells = octree_.cells();
  auto for_each_leaf_in_support = [&](int i, auto&& visit) {
    int stack[8 * (kMaxOctreeDepth + 1)];
    int top = 0;
    stack[top++] = 0;
    const LocalKnots& k = knots_[i];
    while (top > 0) {
      const int c = stack[--top];
      const Octree::Cell& cell = cells[c];
      const int s = octree_.cell_size(cell.level);
      bool overlaps = true;
      for (int a = 0; a < 3; ++a) overlaps &= cell.origin[a] < k[a][4] && cell.origin[a] + s > k[a][0];
      if (!overlaps) continue;
      if (cell.first_child < 0) {
        visit(c);
      } else {
        for (int o = 0; o < 8; ++o) stack[top++] = cell.first_child + o;
      }
    }
  };
  std::vector<int> leaf_of_cell(cells.size(), -1);
  for (int l = 0; l < octree_.leaf_count(); ++l) leaf_of_cell[octree_.leaves()[l]] = l;
  const int L = octree_.leaf_count();
  leaves_.assign(L, LeafSupport{});
  std::vector<std::uint32_t> fill(L + 1, 0);
  for (int i = 0; i < n; ++i) for_each_leaf_in_support(i, [&](int c) { ++fill[leaf_of_cell[c] + 1]; });
  for (int l = 0; l < L; ++l) fill[l + 1] += fill[l];
  std::vector<int> control_of_entry(fill[L]);
  for (int i = 0; i < n; ++i)
    for_each_leaf_in_support(i, [&](int c) { control_of_entry[fill[leaf_of_cell[c]]++] = i; });
  // fill[l] is now the end of leaf l's entries, fill[l - 1] (or 0) its begin.

  // Per leaf: the distinct knot vectors per axis (local numbering through `slot`, reset after each
  // leaf), then the entries sorted into groups of equal (y, z) knot vectors.
  entries_.resize(control_of_entry.size());
  std::vector<int> slot[3];
  for (auto& s : slot) s.assign(knot_vectors_.size(), -1);
  std::vector<std::int32_t> local_ids[3];
  struct Keyed {
    std::uint32_t group_key;
    int control;
    std::uint8_t kx;
  };
  std::vector<Keyed> keyed;
  for (int l = 0; l < L; ++l) {
    const std::uint32_t begin = l == 0 ? 0 : fill[l - 1], end = fill[l];
    keyed.clear();
    for (auto& ids : local_ids) ids.clear();
    for (std::uint32_t e = begin; e < end; ++e) {
      const int i = control_of_entry[e];
      int local[3];
      for (int a = 0; a < 3; ++a) {
        int& k = slot[a][spline_of[i][a]];
        if (k < 0) {
          if (int(local_ids[a].size()) == kMaxLocalSplines) {
            std::ostringstream m;
            m << "T-spline: leaf " << l << " needs more than " << kMaxLocalSplines
              << " distinct knot vectors along one axis; is the T-mesh 2:1 balanced?";
            throw AlgorithmError(m.str());
          }
          k = int(local_ids[a].size());
          local_ids[a].push_back(spline_of[i][a]);
        }
        local[a] = k;
      }
      keyed.push_back({std::uint32_t(local[2] << 8 | local[1]), i, std::uint8_t(local[0])});
    }
    for (int a = 0; a < 3; ++a)
      for (int id : local_ids[a]) slot[a][id] = -1;
    std::stable_sort(keyed.begin(), keyed.end(), [](const Keyed& p, const Keyed& q) { return p.group_key < q.group_key; });
    LeafSupport& leaf = leaves_[l];
    leaf.group_begin = std::uint32_t(groups_.size());
    leaf.entry_begin = begin;
    for (std::uint32_t k = 0; k < keyed.size(); ++k) {
      if (k == 0 || keyed[k].group_key != keyed[k - 1].group_key)  // controls ascend within a group
        groups_.push_back({begin + k, keyed[k].control, std::uint8_t(keyed[k].group_key & 0xff),
                           std::uint8_t(keyed[k].group_key >> 8)});
      const int offset = keyed[k].control - groups_.back().control_base;
      if (offset > 0xffff) throw AlgorithmError("T-spline: support group wider than a lattice row (bug)");
      entries_[begin + k] = {std::uint16_t(offset), keyed[k].kx};
    }
    leaf.group_end = std::uint32_t(groups_.size());
    leaf.spline_begin = std::uint32_t(leaf_splines_.size());
    for (int a = 0; a < 3; ++a) {
      leaf.count[a] = std::uint8_t(local_ids[a].size());
      for (int id : local_ids[a]) leaf_splines_.push_back(knot_vectors_[id]);
    }
  }
  groups_.push_back({std::uint32_t(entries_.size()), 0, 0, 0});  // sentinel
}

KnotValues TSplineBasis::knot_values(int i, int axis) const {
  KnotValues t;
  for (int k = 0; k < 5; ++k) t[k] = octree_.coordinate(axis, knots_[i][axis][k]);
  return t;
}

Vec3 TSplineBasis::greville(int i) const {
  Vec3 g;
  for (int a = 0; a < 3; ++a)
    g[a] = octree_.coordinate(a, (knots_[i][a][1] + knots_[i][a][2] + knots_[i][a][3]) / 3.0);
  return g;
}

std::vector<Vec3> TSplineBasis::greville_points() const {
  std::vector<Vec3> g(size());
  for (int i = 0; i < size(); ++i) g[i] = greville(i);
  return g;
}

double TSplineBasis::blending(int i, const Vec3& x, Vec3* gradient, Mat3* hessian) const {
  double n[3][3];
  for (int a = 0; a < 3; ++a) {
    const KnotValues t = knot_values(i, a);
    for (int d = 0; d < 3; ++d) n[a][d] = cox_de_boor(t, x[a], d);
  }
  if (gradient)
    *gradient = Vec3(n[0][1] * n[1][0] * n[2][0], n[0][0] * n[1][1] * n[2][0], n[0][0] * n[1][0] * n[2][1]);
  if (hessian) {
    Mat3& h = *hessian;
    h(0, 0) = n[0][2] * n[1][0] * n[2][0];
    h(1, 1) = n[0][0] * n[1][2] * n[2][0];
    h(2, 2) = n[0][0] * n[1][0] * n[2][2];
    h(0, 1) = h(1, 0) = n[0][1] * n[1][1] * n[2][0];
    h(0, 2) = h(2, 0) = n[0][1] * n[1][0] * n[2][1];
    h(1, 2) = h(2, 1) = n[0][0] * n[1][1] * n[2][1];
  }
  return n[0][0] * n[1][0] * n[2][0];
}

Vec3 TSplineBasis::clamp(const Vec3& x) const {
  const Vec3& lo = octree_.domain_min();
  const double side = octree_.side();
  Vec3 y;
  for (int a = 0; a < 3; ++a) y[a] = std::min(std::max(x[a], lo[a]), lo[a] + side);  // NaN stays NaN
  return y;
}

namespace {
[[noreturn]] void vanishing_denominator(const Vec3& x) {
  std::ostringstream s;
  s << "T-spline: sum of blending functions is not positive at (" << x.x() << ", " << x.y() << ", "
    << x.z() << ")" << (x.allFinite() ? "" : " (a NaN or infinite coordinate)");
  throw AlgorithmError(s.str());
}
}  // namespace

template <int Order>
void TSplineBasis::evaluate_splines(const LeafSupport& leaf, const Vec3& x,
                                    double (*n)[kMaxLocalSplines][3]) const {
  const LatticeSpline* local = leaf_splines_.data() + leaf.spline_begin;
  const double per_unit = octree_.resolution() / octree_.side();
  for (int a = 0; a < 3; ++a) {
    const double u = (x[a] - octree_.domain_min()[a]) * per_unit;  // lattice coordinate
    for (int k = 0; k < leaf.count[a]; ++k, ++local)
      shapes_[local->shape].evaluate<Order>(u - local->t0, n[a][k][0], n[a][k][1], n[a][k][2]);
  }
}

template <int Order>
double TSplineBasis::evaluate_impl(const double* c, const Vec3& x_in, Vec3* gradient, Mat3* hessian) const {
  const Vec3 x = clamp(x_in);
  const LeafSupport& leaf = leaves_[octree_.locate(x)];
  // Queries in random order miss the cache on every array; start the group and entry loads before
  // the B-spline evaluation needs the cache's attention.
  __builtin_prefetch(groups_.data() + leaf.group_begin);
  __builtin_prefetch(entries_.data() + leaf.entry_begin);
  __builtin_prefetch(entries_.data() + leaf.entry_begin + 16);
  double n[3][kMaxLocalSplines][3];
  evaluate_splines<Order>(leaf, x, n);
  // Sums of B and c B (index 0 and 1) and of their derivatives. B_i = X Y Z factorises, and a group
  // shares Y Z: sum over the group of X, c X, X', c X', X'', c X'' first, then the Y Z factors.
  double s[2] = {0, 0}, g[2][3] = {{0, 0, 0}, {0, 0, 0}}, h[2][6] = {{0}, {0}};  // h: xx yy zz xy xz yz
  const SupportEntry* entries = entries_.data();
  for (std::uint32_t k = leaf.group_begin; k < leaf.group_end; ++k) {
    const SupportGroup& group = groups_[k];
    double x0[2] = {0, 0}, x1[2] = {0, 0}, x2[2] = {0, 0};
    const double* cg = c + group.control_base;
    for (std::uint32_t e = group.entry_begin, end = groups_[k + 1].entry_begin; e < end; ++e) {
      const double* nx = n[0][entries[e].kx];
      const double ci = cg[entries[e].offset];
      x0[0] += nx[0];
      x0[1] += ci * nx[0];
      if (Order >= 1) {
        x1[0] += nx[1];
        x1[1] += ci * nx[1];
      }
      if (Order >= 2) {
        x2[0] += nx[2];
        x2[1] += ci * nx[2];
      }
    }
    const double* ny = n[1][group.ky];
    const double* nz = n[2][group.kz];
    const double yz = ny[0] * nz[0];
    for (int j = 0; j < 2; ++j) s[j] += yz * x0[j];
    if (Order >= 1) {
      const double y1z = ny[1] * nz[0], yz1 = ny[0] * nz[1];
      for (int j = 0; j < 2; ++j) {
        g[j][0] += yz * x1[j];
        g[j][1] += y1z * x0[j];
        g[j][2] += yz1 * x0[j];
      }
      if (Order >= 2) {
        const double y2z = ny[2] * nz[0], yz2 = ny[0] * nz[2], y1z1 = ny[1] * nz[1];
        for (int j = 0; j < 2; ++j) {
          h[j][0] += yz * x2[j];
          h[j][1] += y2z * x0[j];
          h[j][2] += yz2 * x0[j];
          h[j][3] += y1z * x1[j];
          h[j][4] += yz1 * x1[j];
          h[j][5] += y1z1 * x0[j];
        }
      }
    }
  }
  if (!(s[0] > 0.0)) vanishing_denominator(x_in);
  // f = S1/S0;  grad f = (G1 - f G0)/S0;  H f = (H1 - f H0 - grad f G0^T - G0 grad f^T)/S0, all in
  // lattice units, then per world unit.
  const double inv = 1.0 / s[0];
  const double f = s[1] * inv;
  if (Order >= 1) {
    const double per_unit = octree_.resolution() / octree_.side();
    double df[3];
    for (int a = 0; a < 3; ++a) df[a] = (g[1][a] - f * g[0][a]) * inv;
    if (gradient) *gradient = per_unit * Vec3(df[0], df[1], df[2]);
    if (Order >= 2 && hessian) {
      static constexpr int row[6] = {0, 1, 2, 0, 0, 1}, col[6] = {0, 1, 2, 1, 2, 2};
      const double scale = inv * per_unit * per_unit;
      for (int k = 0; k < 6; ++k) {
        const int r = row[k], q = col[k];
        const double v = (h[1][k] - f * h[0][k] - df[r] * g[0][q] - g[0][r] * df[q]) * scale;
        (*hessian)(r, q) = (*hessian)(q, r) = v;
      }
    }
  }
  return f;
}

double TSplineBasis::evaluate(const double* c, const Vec3& x, Vec3* gradient, Mat3* hessian) const {
  if (hessian) return evaluate_impl<2>(c, x, gradient, hessian);
  if (gradient) return evaluate_impl<1>(c, x, gradient, nullptr);
  return evaluate_impl<0>(c, x, nullptr, nullptr);
}

void TSplineBasis::active(const Vec3& x_in, ActiveBasis& out, bool hessians) const {
  const Vec3 x = clamp(x_in);
  out.leaf = octree_.locate(x);
  const LeafSupport& leaf = leaves_[out.leaf];
  double n[3][kMaxLocalSplines][3];
  if (hessians) {
    evaluate_splines<2>(leaf, x, n);
  } else {
    evaluate_splines<1>(leaf, x, n);
  }
  out.index.clear();
  out.value.clear();
  out.gradient.clear();
  out.hessian.clear();
  double s0 = 0;
  Vec3 g0 = Vec3::Zero();
  Mat3 h0 = Mat3::Zero();
  for (std::uint32_t k = leaf.group_begin; k < leaf.group_end; ++k) {
    const double* ny = n[1][groups_[k].ky];
    const double* nz = n[2][groups_[k].kz];
    for (std::uint32_t e = groups_[k].entry_begin; e < groups_[k + 1].entry_begin; ++e) {
      const double* nx = n[0][entries_[e].kx];
      const double b = nx[0] * ny[0] * nz[0];
      if (!(b > 0.0)) continue;  // outside this function's support (its derivatives vanish there too)
      const Vec3 g(nx[1] * ny[0] * nz[0], nx[0] * ny[1] * nz[0], nx[0] * ny[0] * nz[1]);
      out.index.push_back(groups_[k].control_base + entries_[e].offset);
      out.value.push_back(b);
      out.gradient.push_back(g);
      s0 += b;
      g0 += g;
      if (hessians) {
        Mat3 h;
        h(0, 0) = nx[2] * ny[0] * nz[0];
        h(1, 1) = nx[0] * ny[2] * nz[0];
        h(2, 2) = nx[0] * ny[0] * nz[2];
        h(0, 1) = h(1, 0) = nx[1] * ny[1] * nz[0];
        h(0, 2) = h(2, 0) = nx[1] * ny[0] * nz[1];
        h(1, 2) = h(2, 1) = nx[0] * ny[1] * nz[1];
        out.hessian.push_back(h);
        h0 += h;
      }
    }
  }
  if (!(s0 > 0.0)) vanishing_denominator(x_in);
  out.denominator = s0;
  // R_i = B_i/S;  grad R_i = (grad B_i - R_i G)/S;  H R_i = (H B_i - R_i H0 - grad R_i G^T - G grad R_i^T)/S,
  // in lattice units, then per world unit. (The denominator reported is the same in either.)
  const double inv = 1.0 / s0;
  const double per_unit = octree_.resolution() / octree_.side();
  for (int k = 0; k < out.size(); ++k) {
    const double r = out.value[k] * inv;
    const Vec3 gr = (out.gradient[k] - r * g0) * inv;
    out.value[k] = r;
    out.gradient[k] = per_unit * gr;
    if (hessians)
      out.hessian[k] = (out.hessian[k] - r * h0 - gr * g0.transpose() - g0 * gr.transpose()) * (inv * per_unit * per_unit);
  }
}

std::vector<char> TSplineBasis::positive_leaves(const double* c) const {
  std::vector<char> positive(leaves_.size(), 1);
  for (std::size_t l = 0; l < leaves_.size(); ++l)
    for (std::uint32_t k = leaves_[l].group_begin; k < leaves_[l].group_end && positive[l]; ++k)
      for (std::uint32_t e = groups_[k].entry_begin; e < groups_[k + 1].entry_begin; ++e)
        if (!(c[groups_[k].control_base + entries_[e].offset] > 0.0)) {
          positive[l] = 0;
          break;
        }
  return positive;
}

std::vector<int> TSplineBasis::support(int leaf) const {
  std::vector<int> s;
  for (std::uint32_t k = leaves_[leaf].group_begin; k < leaves_[leaf].group_end; ++k)
    for (std::uint32_t e = groups_[k].entry_begin; e < groups_[k + 1].entry_begin; ++e)
      s.push_back(groups_[k].control_base + entries_[e].offset);
  std::sort(s.begin(), s.end());
  return s;
}

TSplineBasis::Stats TSplineBasis::stats() const {
  Stats s;
  s.control_points = size();
  s.leaves = octree_.leaf_count();
  s.distinct_knot_vectors = int(knot_vectors_.size());
  s.shapes = int(shapes_.size());
  double total = 0, groups = 0;
  for (int l = 0; l < s.leaves; ++l) {
    total += support_size(l);
    groups += leaves_[l].group_end - leaves_[l].group_begin;
    s.max_support = std::max(s.max_support, support_size(l));
    for (int a = 0; a < 3; ++a) s.max_local_splines = std::max(s.max_local_splines, int(leaves_[l].count[a]));
  }
  s.mean_support = s.leaves > 0 ? total / s.leaves : 0.0;
  s.mean_groups = s.leaves > 0 ? groups / s.leaves : 0.0;
  return s;
}

}  // namespace dtsl
