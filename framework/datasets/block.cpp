// `block`: a CAD-like part with exact ground truth — a rectangular block with a cylindrical through-hole
// along z. It has what the paper's sharpening phase is for: sharp convex edges (the box's 12 edges),
// sharp edges next to a curved face (the two hole rims), flat faces and a curved face, and genus 1.
//
// Built directly rather than by a CSG library, so that every face is tessellated with vertices about
// `edge_length` apart: the `vertices` sampler (the paper's inputs are scan vertices) then gives an
// evenly dense point set, which a box-minus-cylinder from corefinement (a few long triangles per face)
// would not. Layout of the top face (z = +h; the bottom mirrors it): N points along the outer
// rectangle, the rectangle's corners among them, and rings of points between the hole's circle and the
// rectangle. Near the hole the rings have N/2, N/4, ... points (one 1:2 transition strip per halving),
// so the spacing along the circle stays close to edge_length instead of shrinking by the ratio of the
// perimeters. The outer walls and the hole's wall are grids of quads sharing the face rings.
#include <algorithm>
#include <cmath>

#include "framework/core/error.hpp"
#include "framework/datasets/dataset.hpp"
#include "framework/datasets/internal.hpp"

namespace dtsl::dataset_detail {

namespace {

struct BlockOptions final : Options {
  double length = 2.0;
  double width = 1.4;
  double height = 0.8;
  double hole_radius = 0.35;
  double edge_length = 0.03;

  void visit(FieldVisitor& v) override {
    v.field("length", length, "size along x (shape frame; the block is then normalised into [-1,1]^3)");
    v.field("width", width, "size along y");
    v.field("height", height, "size along z, the axis of the hole");
    v.field("hole_radius", hole_radius, "radius of the cylindrical through-hole centred on the z axis");
    v.field("edge_length", edge_length,
            "target spacing of the vertices (sets the `vertices` sampler's density; 0.03: about 14k vertices)");
  }
  void check() const override {
    check_positive("length", length);
    check_positive("width", width);
    check_positive("height", height);
    check_positive("hole_radius", hole_radius);
    // Leave a wall of at least a fifth of the half-width around the hole, else it is a thin sliver.
    const double max_radius = 0.4 * std::min(length, width);
    require(hole_radius <= max_radius, "hole_radius",
            "must be at most 0.4 * min(length, width) = " + format_number(max_radius) +
                " to leave a wall around the hole, got " + format_number(hole_radius));
    check_positive("edge_length", edge_length);
    const double smallest = std::min({length, width, height});
    require(edge_length <= 0.5 * smallest, "edge_length",
            "must be at most half the smallest size (" + format_number(0.5 * smallest) + "), got " +
                format_number(edge_length));
    const double area = 2.0 * (length * width - M_PI * hole_radius * hole_radius) +
                        height * (2.0 * (length + width) + 2.0 * M_PI * hole_radius);
    const double vertices = area / (edge_length * edge_length);
    require(vertices <= 4e6, "edge_length",
            "too small for this block: about " + format_number(std::round(vertices)) +
                " vertices (at most 4000000), got " + format_number(edge_length));
  }
};

/// Splits the quad (a, b, c, d), given counter-clockwise seen from outside, along its shorter diagonal:
/// the better-shaped pair of triangles.
void add_quad(TriangleMesh& m, int a, int b, int c, int d) {
  const auto& v = m.vertices;
  if ((v[a] - v[c]).squaredNorm() <= (v[b] - v[d]).squaredNorm()) {
    m.faces.push_back({a, b, c});
    m.faces.push_back({a, c, d});
  } else {
    m.faces.push_back({a, b, d});
    m.faces.push_back({b, c, d});
  }
}

TriangleMesh block_mesh(const BlockOptions& o) {
  const double a = 0.5 * o.length, b = 0.5 * o.width, h = 0.5 * o.height, rh = o.hole_radius;
  const double e = o.edge_length;
  const double perimeter = 4.0 * (a + b);

  // Points on the rectangle, counter-clockwise from (a, 0), with the four corners among them. Segment
  // counts are rounded from their lengths.
  const Vec3 corners[6] = {{a, 0, 0}, {a, b, 0}, {-a, b, 0}, {-a, -b, 0}, {a, -b, 0}, {a, 0, 0}};
  int count[5];
  for (int s = 0; s < 5; ++s)
    count[s] = std::max(1, static_cast<int>(std::lround((corners[s + 1] - corners[s]).norm() / e)));
  int n_total = count[0] + count[1] + count[2] + count[3] + count[4];

  // Halvings between the rectangle (N points) and the circle (N / 2^q points): the circle should get
  // about perimeter-ratio times fewer points to keep its spacing near e, but never fewer than 16, or a
  // small hole would become a polygon of a few sides.
  int q = std::max(0, static_cast<int>(std::lround(std::log2(perimeter / (2.0 * M_PI * rh)))));
  while (q > 0 && n_total / (1 << q) < 16) --q;
  const int stride_q = 1 << q;
  // The longest segments grow until 2^q divides N.
  for (int s = 1; n_total % stride_q != 0; s = s % 4 + 1) {  // grow the long sides in turn: 1, 2, 3, 4
    ++count[s];
    ++n_total;
  }
  const int N = n_total;
  std::vector<Vec3> square;    // S_k, k = 0..N-1
  std::vector<double> arc;     // perimeter position of S_k
  double walked = 0.0;
  for (int s = 0; s < 5; ++s) {
    const double len = (corners[s + 1] - corners[s]).norm();
    for (int i = 0; i < count[s]; ++i) {
      const double t = static_cast<double>(i) / count[s];
      square.push_back((1.0 - t) * corners[s] + t * corners[s + 1]);
      arc.push_back(walked + t * len);
    }
    walked += len;
  }
  // C_k: the circle point paired with S_k, at the same fraction of the way around. The pairs' segments
  // are close to radial (exactly at the corners of a square and the side midpoints), never crossing.
  auto circle = [&](int k) {
    const double phi = 2.0 * M_PI * arc[k] / perimeter;
    return Vec3(rh * std::cos(phi), rh * std::sin(phi), 0.0);
  };

  // Rings of the top face: t_j from 0 (circle) to 1 (rectangle), uniform; ring j has N / 2^m_j points.
  double mean_gap = 0.0;
  for (int k = 0; k < N; ++k) mean_gap += (square[k] - circle(k)).norm();
  mean_gap /= N;
  const int M = std::max({1, q, static_cast<int>(std::lround(mean_gap / e))});
  std::vector<int> level(M + 1);
  for (int j = 0; j <= M; ++j) {
    const double t = static_cast<double>(j) / M;
    const double circumference = (1.0 - t) * 2.0 * M_PI * rh + t * perimeter;
    const double ideal = std::log2(N * e / circumference);
    level[j] = std::clamp(static_cast<int>(std::lround(ideal)), 0, q);
  }
  level[0] = q;
  for (int j = 0; j < M; ++j) level[j + 1] = std::clamp(level[j + 1], level[j] - 1, level[j]);  // halve at most once per strip
  for (int j = 0; j <= M; ++j) level[j] = std::min(level[j], M - j);  // reach N points at the rectangle

  TriangleMesh m;
  auto add_vertex = [&](const Vec3& p) {
    m.vertices.push_back(p);
    return static_cast<int>(m.vertices.size()) - 1;
  };

  // ring[side][j][i]: vertex of point i (perimeter index k = i * 2^level[j]) of ring j on the top
  // (side 0) or bottom (side 1) face.
  std::vector<std::vector<int>> ring[2];
  for (int side = 0; side < 2; ++side) {
    const double z = side == 0 ? h : -h;
    ring[side].resize(M + 1);
    for (int j = 0; j <= M; ++j) {
      const double t = static_cast<double>(j) / M;
      const int stride = 1 << level[j];
      for (int k = 0; k < N; k += stride) {
        Vec3 p = (1.0 - t) * circle(k) + t * square[k];
        if (j == M) p = square[k];  // exact corners, no rounding
        p.z() = z;
        ring[side][j].push_back(add_vertex(p));
      }
    }
  }

  // Faces between rings j and j+1. For the top, (inner i -> outer -> outer next -> inner next) is
  // counter-clockwise seen from +z; the bottom face uses the reverse.
  for (int side = 0; side < 2; ++side) {
    auto tri = [&](int x, int y, int z) {
      if (side == 0) m.faces.push_back({x, y, z});
      else m.faces.push_back({x, z, y});
    };
    for (int j = 0; j < M; ++j) {
      const std::vector<int>& in = ring[side][j];
      const std::vector<int>& out = ring[side][j + 1];
      const int n_in = static_cast<int>(in.size());
      const int n_out = static_cast<int>(out.size());
      if (n_in == n_out) {
        for (int i = 0; i < n_in; ++i) {
          const int i1 = (i + 1) % n_in;
          if (side == 0) add_quad(m, in[i], out[i], out[i1], in[i1]);
          else add_quad(m, in[i], in[i1], out[i1], out[i]);
        }
      } else {  // 1:2 transition: three triangles per inner interval
        for (int i = 0; i < n_in; ++i) {
          const int i1 = (i + 1) % n_in;
          const int o0 = out[2 * i], om = out[2 * i + 1], o1 = out[(2 * i + 2) % n_out];
          tri(in[i], o0, om);
          tri(in[i], om, in[i1]);
          tri(in[i1], om, o1);
        }
      }
    }
  }

  // A vertical wall of quads between the bottom ring `bottom` and the top ring `top` (same length),
  // `layers` quads high; `outward` = true when (column k -> k+1) runs counter-clockwise seen from the
  // side the wall faces. Returns the vertices it added (the rows between the rings).
  auto wall = [&](const std::vector<int>& bottom, const std::vector<int>& top, int layers, bool outward) {
    std::vector<int> added;
    const int n = static_cast<int>(bottom.size());
    std::vector<std::vector<int>> rows(layers + 1);
    rows[0] = bottom;
    rows[layers] = top;
    for (int l = 1; l < layers; ++l) {
      const double t = static_cast<double>(l) / layers;
      for (int k = 0; k < n; ++k) {
        rows[l].push_back(add_vertex((1.0 - t) * m.vertices[bottom[k]] + t * m.vertices[top[k]]));
        added.push_back(rows[l].back());
      }
    }
    for (int l = 0; l < layers; ++l)
      for (int k = 0; k < n; ++k) {
        const int k1 = (k + 1) % n;
        if (outward) add_quad(m, rows[l][k], rows[l][k1], rows[l + 1][k1], rows[l + 1][k]);
        else add_quad(m, rows[l][k], rows[l + 1][k], rows[l + 1][k1], rows[l][k1]);
      }
    return added;
  };
  const int outer_layers = std::max(1, static_cast<int>(std::lround(2.0 * h / e)));
  wall(ring[1][M], ring[0][M], outer_layers, true);
  // The hole's wall faces the axis, so its outside is seen from within the hole: reversed order.
  const double hole_spacing = 2.0 * M_PI * rh / static_cast<double>(ring[0][0].size());
  const int hole_layers = std::max(1, static_cast<int>(std::lround(2.0 * h / hole_spacing)));
  const std::vector<int> hole_wall = wall(ring[1][0], ring[0][0], hole_layers, false);

  // Flat faces: angle weighting gives exactly their normal however the triangles are cut. The hole's
  // wall: the cylinder's own normal (towards the axis), which averaging facets of unequal width would
  // miss by a little. At sharp edges the normal is a choice, not a property of the shape: the bisector
  // of the two faces (what angle weighting gives on the box's edges; set explicitly on the hole's rims).
  m.normals = angle_weighted_vertex_normals(m);
  auto radial_in = [&](int v) { return Vec3(-m.vertices[v].x(), -m.vertices[v].y(), 0.0).normalized(); };
  for (const int v : hole_wall) m.normals[v] = radial_in(v);
  for (int side = 0; side < 2; ++side)
    for (const int v : ring[side][0]) m.normals[v] = (radial_in(v) + Vec3(0, 0, side == 0 ? 1.0 : -1.0)).normalized();
  return m;
}

class Block final : public ShapeSource {
 public:
  Options& options() override { return o_; }
  ShapeData load() override {
    ShapeData d;
    d.mesh = block_mesh(o_);
    d.exact = true;
    return d;
  }

 private:
  BlockOptions o_;
};

}  // namespace

void register_block_shape() {
  shape_sources().add("block", "box with a cylindrical through-hole along z: sharp edges, genus 1",
                      [] { return std::make_unique<Block>(); });
}

}  // namespace dtsl::dataset_detail
