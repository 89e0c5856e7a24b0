// Ground truth of the implicit shape families, in two steps:
//  1. Marching tetrahedra on a body-centred cubic lattice of spacing 2 edge_length: the zero set of the
//     piecewise-linear interpolant of f on a tetrahedral mesh is always a closed, oriented 2-manifold
//     (no ambiguous case, unlike marching cubes), with f's topology wherever the lattice resolves the
//     shape's features. Its triangles are uneven (slivers where the surface passes near a lattice point).
//  2. CGAL's isotropic remeshing to edge_length (splits, link-condition collapses and flips, which keep
//     the topology; tangential relaxation), each new or moved vertex projected onto {f = 0} by Newton
//     steps, so the vertices lie on the exact surface and the triangles are close to equilateral.
// The vertices carry f's normalised gradient as normals. The topology is then checked against what the
// shape claims, so a lattice too coarse for the shape's thinnest feature is an error, never a wrong
// ground truth. Everything is deterministic (no random choice, no pointer-ordered container).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "framework/core/error.hpp"
#include "framework/datasets/internal.hpp"
#include "framework/metrics/metrics.hpp"

namespace dtsl::dataset_detail {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Function = std::function<double(const Vec3&)>;

Vec3 central_gradient(const Function& f, const Vec3& p, double h) {
  Vec3 g;
  for (int k = 0; k < 3; ++k) {
    Vec3 a = p, b = p;
    a[k] += h;
    b[k] -= h;
    g[k] = (f(a) - f(b)) / (2.0 * h);
  }
  return g;
}

/// Newton steps along the gradient onto {f = 0}; f is distance-like near its zero set, so a few steps
/// from within an edge length reach it to rounding.
Vec3 project(const Function& f, Vec3 p, double h, double tolerance) {
  for (int it = 0; it < 30; ++it) {
    const double v = f(p);
    if (std::abs(v) <= tolerance) break;
    const Vec3 g = central_gradient(f, p, h);
    const double g2 = g.squaredNorm();
    if (!(g2 > 0.0)) break;
    p -= (v / g2) * g;
  }
  return p;
}

/// The body-centred cubic lattice over a box: the corners of n[0] x n[1] x n[2] cubes of side h and
/// their centres. Its tetrahedra (two adjacent cube centres and an edge of the face between them) are
/// all congruent, which keeps marching tetrahedra's triangles from the worst shapes of a cube split.
struct Lattice {
  Vec3 origin;
  double h;
  int n[3];

  long corners() const { return static_cast<long>(n[0] + 1) * (n[1] + 1) * (n[2] + 1); }
  long corner(int i, int j, int k) const { return i + static_cast<long>(n[0] + 1) * (j + static_cast<long>(n[1] + 1) * k); }
  long centre(int i, int j, int k) const { return corners() + i + static_cast<long>(n[0]) * (j + static_cast<long>(n[1]) * k); }
  long size() const { return corners() + static_cast<long>(n[0]) * n[1] * n[2]; }
  Vec3 position(long id) const {
    if (id < corners()) {
      const long i = id % (n[0] + 1), j = (id / (n[0] + 1)) % (n[1] + 1), k = id / ((n[0] + 1) * static_cast<long>(n[1] + 1));
      return origin + h * Vec3(i, j, k);
    }
    id -= corners();
    const long i = id % n[0], j = (id / n[0]) % n[1], k = id / (n[0] * static_cast<long>(n[1]));
    return origin + h * Vec3(i + 0.5, j + 0.5, k + 0.5);
  }
};

/// Marching tetrahedra: the zero set of the interpolant of `value` (inside: value < 0), faces oriented
/// towards the positive side.
TriangleMesh marching_tetrahedra(const Lattice& L, const std::vector<double>& value) {
  TriangleMesh m;
  std::unordered_map<std::uint64_t, int> crossing;  // lattice edge (a * size + b, a < b) -> vertex
  const std::uint64_t size = static_cast<std::uint64_t>(L.size());
  auto vertex_on = [&](long inside, long outside) {
    const long a = std::min(inside, outside), b = std::max(inside, outside);
    const std::uint64_t key = static_cast<std::uint64_t>(a) * size + static_cast<std::uint64_t>(b);
    auto [it, added] = crossing.emplace(key, static_cast<int>(m.vertices.size()));
    if (added) {
      const double fa = value[inside], fb = value[outside];
      // Kept off the lattice points: a crossing at a point would give zero-length edges; the remeshing
      // and projection move it onto the surface anyway.
      const double t = std::clamp(fa / (fa - fb), 0.05, 0.95);
      m.vertices.push_back((1.0 - t) * L.position(inside) + t * L.position(outside));
    }
    return it->second;
  };
  auto add = [&](int a, int b, int c, const Vec3& towards_outside) {
    const Vec3 n = (m.vertices[b] - m.vertices[a]).cross(m.vertices[c] - m.vertices[a]);
    if (n.dot(towards_outside) >= 0.0) m.faces.push_back({a, b, c});
    else m.faces.push_back({a, c, b});
  };
  auto tetrahedron = [&](const long v[4]) {
    long in[4], out[4];
    int ni = 0, no = 0;
    for (int k = 0; k < 4; ++k) (value[v[k]] < 0.0 ? in[ni++] : out[no++]) = v[k];
    if (ni == 0 || no == 0) return;
    Vec3 ci = Vec3::Zero(), co = Vec3::Zero();
    for (int k = 0; k < ni; ++k) ci += L.position(in[k]) / ni;
    for (int k = 0; k < no; ++k) co += L.position(out[k]) / no;
    const Vec3 dir = co - ci;
    if (ni == 1) {
      add(vertex_on(in[0], out[0]), vertex_on(in[0], out[1]), vertex_on(in[0], out[2]), dir);
    } else if (no == 1) {
      add(vertex_on(in[0], out[0]), vertex_on(in[1], out[0]), vertex_on(in[2], out[0]), dir);
    } else {  // a quad: a cycle through the four crossing edges, split along its shorter diagonal
      const int q0 = vertex_on(in[0], out[0]), q1 = vertex_on(in[0], out[1]);
      const int q2 = vertex_on(in[1], out[1]), q3 = vertex_on(in[1], out[0]);
      if ((m.vertices[q0] - m.vertices[q2]).squaredNorm() <= (m.vertices[q1] - m.vertices[q3]).squaredNorm()) {
        add(q0, q1, q2, dir);
        add(q0, q2, q3, dir);
      } else {
        add(q0, q1, q3, dir);
        add(q1, q2, q3, dir);
      }
    }
  };
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    int c[3];
    for (c[2] = 0; c[2] < L.n[2]; ++c[2])
      for (c[1] = 0; c[1] < L.n[1]; ++c[1])
        for (c[0] = 0; c[0] < L.n[0]; ++c[0]) {
          int d[3] = {c[0], c[1], c[2]};
          ++d[axis];
          if (d[axis] >= L.n[axis]) continue;  // no neighbour cube: the face is on the lattice's boundary
          const long ca = L.centre(c[0], c[1], c[2]), cb = L.centre(d[0], d[1], d[2]);
          // The shared face's corners, in cyclic order.
          long face[4];
          const int du[4] = {0, 1, 1, 0}, dw[4] = {0, 0, 1, 1};
          for (int q = 0; q < 4; ++q) {
            int p[3] = {d[0], d[1], d[2]};
            p[u] += du[q];
            p[w] += dw[q];
            face[q] = L.corner(p[0], p[1], p[2]);
          }
          for (int q = 0; q < 4; ++q) {
            const long tet[4] = {ca, cb, face[q], face[(q + 1) % 4]};
            tetrahedron(tet);
          }
        }
  }
  return m;
}

}  // namespace

TriangleMesh mesh_implicit_surface(const ImplicitSurface& s, double edge_length, const std::string& what) {
  const Function& f = s.f;
  const double scale = s.box.diagonal();
  const double h = 1e-7 * scale, tolerance = 1e-13 * scale;

  // The lattice: spacing twice the edge length (marching tetrahedra's vertices are then about as dense as
  // the remeshed ones, so the remeshing has little to collapse, and a feature 4 edge lengths thick still
  // spans two lattice spacings); one spacing of margin around the box, so no tetrahedron the surface
  // crosses is cut off.
  Lattice L;
  L.h = 2.0 * edge_length;
  L.origin = s.box.min - Vec3::Constant(L.h);
  for (int k = 0; k < 3; ++k) L.n[k] = static_cast<int>(std::ceil(s.box.extent()[k] / L.h)) + 2;
  std::vector<double> value(static_cast<std::size_t>(L.size()));
  for (long id = 0; id < L.size(); ++id) value[id] = f(L.position(id));

  const TriangleMesh raw = marching_tetrahedra(L, value);
  if (raw.faces.empty()) throw AlgorithmError(what + ": the implicit surface crosses no lattice edge");

  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> vi;
  vi.reserve(raw.vertices.size());
  for (const Vec3& p : raw.vertices) vi.push_back(sm.add_vertex(Point(p.x(), p.y(), p.z())));
  for (const Face& t : raw.faces)
    if (sm.add_face(vi[t[0]], vi[t[1]], vi[t[2]]) == SurfaceMesh::null_face())
      throw AlgorithmError(what + ": marching tetrahedra gave a non-manifold surface");

  auto points = sm.points();
  const auto projection = [&](SurfaceMesh::Vertex_index v) {
    const Point& p = points[v];
    const Vec3 q = project(f, Vec3(p.x(), p.y(), p.z()), h, tolerance);
    return Point(q.x(), q.y(), q.z());
  };
  for (const SurfaceMesh::Vertex_index v : sm.vertices()) points[v] = projection(v);
  namespace PMP = CGAL::Polygon_mesh_processing;
  PMP::isotropic_remeshing(sm.faces(), edge_length, sm,
                           CGAL::parameters::number_of_iterations(3).projection_functor(projection));
  sm.collect_garbage();

  TriangleMesh m;
  std::vector<int> index(sm.number_of_vertices());
  for (const SurfaceMesh::Vertex_index v : sm.vertices()) {
    index[v] = static_cast<int>(m.vertices.size());
    const Point& p = points[v];
    m.vertices.push_back(project(f, Vec3(p.x(), p.y(), p.z()), h, tolerance));
  }
  for (const SurfaceMesh::Face_index fi : sm.faces()) {
    Face t;
    int k = 0;
    for (const SurfaceMesh::Vertex_index v : sm.vertices_around_face(sm.halfedge(fi))) t[k++] = index[v];
    m.faces.push_back(t);
  }
  m.normals.reserve(m.vertices.size());
  for (const Vec3& p : m.vertices) {
    const Vec3 g = central_gradient(f, p, h);
    if (!(g.norm() > 0.0)) throw AlgorithmError(what + ": the implicit function has a zero gradient on its surface");
    m.normals.push_back(g.normalized());
  }

  // What the shape promises must hold: a closed manifold with its components and genus.
  const MeshStats t = mesh_stats(m);
  if (!t.watertight || t.components != static_cast<std::size_t>(s.components) || t.genus != s.genus)
    throw AlgorithmError(what + ": the mesh of the surface has " +
                         (t.watertight ? "" : "boundary or non-manifold edges, ") + std::to_string(t.components) +
                         " component(s) and Euler characteristic " + std::to_string(t.euler_characteristic) +
                         ", not the shape's " + std::to_string(s.components) + " component(s) of genus " +
                         std::to_string(s.genus) + "; edge_length " + format_number(edge_length) +
                         " is too coarse for its thinnest feature");
  return m;
}

}  // namespace dtsl::dataset_detail
