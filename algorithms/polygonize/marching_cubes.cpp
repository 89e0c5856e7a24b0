#include "algorithms/polygonize/marching_cubes.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numeric>
#include <unordered_map>

#include "algorithms/polygonize/seeding.hpp"
#include "framework/core/connected_components.hpp"
#include "framework/core/error.hpp"
#include "framework/core/mesh_adjacency.hpp"
#include "framework/core/timer.hpp"
#include "framework/core/union_find.hpp"

namespace dtsl {

void MarchingCubesOptions::visit(FieldVisitor& v) {
  v.field("step", step, "grid spacing delta in the [-1,1] frame");
  v.field("region", region, "grid region: domain (f's domain box) | data (data bounding box + margin)");
  v.field("margin", margin, "growth of the data box for region = data (frame units)");
  v.field("vertex_placement", vertex_placement,
          "vertex on a grid edge: linear (interpolate the samples) | root (regula falsi to f = 0 on the edge)");
  v.field("newton_project", newton_project,
          "also move every vertex onto f = 0 by Newton (off its grid edge; slivers may then cross)");
  v.field("drop_dataless_components", drop_dataless_components,
          "with data points, keep only components some data foot point lies on");
  v.field("cover_distance", cover_distance, "x step: a foot point this close to a component marks it as carrying data");
  v.field("max_grid_nodes", max_grid_nodes, "cap on the number of grid samples (above: AlgorithmError)");
  v.field("newton_tolerance", newton_tolerance, "Newton projection onto f = 0: stop when |f|/|grad f| is below this");
  v.field("newton_max_iterations", newton_max_iterations, "Newton projection: iteration cap");
}

void MarchingCubesOptions::check() const {
  check_range("step", step, 1e-4, 0.5);
  check_one_of("region", region, {"domain", "data"});
  check_range("margin", margin, 0.0, 1.0);
  check_one_of("vertex_placement", vertex_placement, {"linear", "root"});
  check_range("cover_distance", cover_distance, 0.01, 2.0);
  check_range("max_grid_nodes", max_grid_nodes, 8, 2'000'000'000);
  newton().check();
}

NewtonOptions MarchingCubesOptions::newton() const {
  NewtonOptions n;
  n.tolerance = newton_tolerance;
  n.max_iterations = newton_max_iterations;
  return n;
}

namespace {

// Where the level set passes (almost) through a grid node, every edge around the node gets a vertex
// (almost) on it: a cluster of near-coincident vertices whose tiny triangles cross each other under
// the slightest perturbation. A sample within kOffZero x (its largest difference to an axis
// neighbour, ~ |grad f| h) of zero is therefore moved to +kOffZero x that difference (outside).
// Vertices then keep a distance of about kOffZero / 4 of an edge from the nodes, and the surface
// moves by at most ~kOffZero h there. kEdgeClamp keeps refined roots off the nodes by the same margin.
constexpr double kOffZero = 0.005;
constexpr double kEdgeClamp = kOffZero / 4;

struct Grid {
  Vec3 origin;
  double h = 0.0;
  int nx = 0, ny = 0, nz = 0;
  long index(int i, int j, int k) const { return (static_cast<long>(k) * ny + j) * nx + i; }
  Vec3 position(int i, int j, int k) const { return origin + h * Vec3(i, j, k); }
  long nodes() const { return static_cast<long>(nx) * ny * nz; }
};

/// The grid over `box`, centred on it, spacing exactly h (the box is grown to a whole number of cells).
Grid make_grid(const BoundingBox& box, double h, long max_nodes) {
  Grid g;
  g.h = h;
  Eigen::Vector3i n;
  double total = 1.0;
  for (int a = 0; a < 3; ++a) {
    const double cells = std::ceil(box.extent()[a] / h - 1e-9);
    n[a] = static_cast<int>(std::max(1.0, cells)) + 1;
    total *= n[a];
  }
  if (total > static_cast<double>(max_nodes))
    throw AlgorithmError("marching_cubes: a grid of step " + std::to_string(h) + " over the region needs " +
                         std::to_string(static_cast<long>(total)) + " samples (max_grid_nodes = " +
                         std::to_string(max_nodes) + "); raise step or max_grid_nodes");
  g.nx = n.x();
  g.ny = n.y();
  g.nz = n.z();
  g.origin = box.center() - 0.5 * h * Vec3(g.nx - 1, g.ny - 1, g.nz - 1);
  return g;
}

/// A vertex on the grid edge from node a to node b, before placement.
struct EdgeVertex {
  Vec3 pa, pb;
  double va, vb;
};

// The six Kuhn tetrahedra of a cube (corners as bit masks x = 1, y = 2, z = 4): monotone paths from
// corner 0 to corner 7, one per order of the axes. Every tetrahedron edge joins a corner to a corner
// with a superset of its bits, so an edge is named by its lower node and the bits it adds.
constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

int popcount3(int bits) { return (bits & 1) + ((bits >> 1) & 1) + ((bits >> 2) & 1); }

class Extractor {
 public:
  Extractor(const Grid& g, const std::vector<double>& values) : g_(g), values_(values) {}

  void run() {
    for (int k = 0; k + 1 < g_.nz; ++k)
      for (int j = 0; j + 1 < g_.ny; ++j)
        for (int i = 0; i + 1 < g_.nx; ++i) cube(i, j, k);
  }

  std::vector<EdgeVertex> vertices;
  std::vector<Face> faces;

 private:
  static Vec3 corner(int bits) { return Vec3(bits & 1, (bits >> 1) & 1, (bits >> 2) & 1); }

  int vertex(int i, int j, int k, int a, int b) {
    if (popcount3(a) > popcount3(b)) std::swap(a, b);
    const int ia = i + (a & 1), ja = j + ((a >> 1) & 1), ka = k + ((a >> 2) & 1);
    const int ib = i + (b & 1), jb = j + ((b >> 1) & 1), kb = k + ((b >> 2) & 1);
    const std::uint64_t key = static_cast<std::uint64_t>(g_.index(ia, ja, ka)) * 8u + static_cast<std::uint64_t>(a ^ b);
    const auto it = index_.find(key);
    if (it != index_.end()) return it->second;
    EdgeVertex e{g_.position(ia, ja, ka), g_.position(ib, jb, kb), values_[static_cast<std::size_t>(g_.index(ia, ja, ka))],
                 values_[static_cast<std::size_t>(g_.index(ib, jb, kb))]};
    vertices.push_back(e);
    const int id = static_cast<int>(vertices.size()) - 1;
    index_.emplace(key, id);
    return id;
  }

  /// Emits the triangle through the vertices on corner-pair edges e[0..2], oriented so its normal
  /// points from the inside corners to the outside ones. The orientation is decided on the edge
  /// midpoints, where the triangle is never degenerate, so it is exact whatever the placement.
  void triangle(int i, int j, int k, const std::array<std::pair<int, int>, 3>& e, const Vec3& out_dir) {
    std::array<Vec3, 3> m;
    std::array<int, 3> v;
    for (int s = 0; s < 3; ++s) {
      m[static_cast<std::size_t>(s)] = 0.5 * (corner(e[static_cast<std::size_t>(s)].first) + corner(e[static_cast<std::size_t>(s)].second));
      v[static_cast<std::size_t>(s)] = vertex(i, j, k, e[static_cast<std::size_t>(s)].first, e[static_cast<std::size_t>(s)].second);
    }
    if ((m[1] - m[0]).cross(m[2] - m[0]).dot(out_dir) < 0.0) std::swap(v[1], v[2]);
    faces.push_back({{v[0], v[1], v[2]}});
  }

  static Vec3 linear_point(const EdgeVertex& e) { return e.pa + (e.va / (e.va - e.vb)) * (e.pb - e.pa); }

  void cube(int i, int j, int k) {
    std::array<double, 8> val;
    int inside = 0;
    for (int c = 0; c < 8; ++c) {
      val[static_cast<std::size_t>(c)] = values_[static_cast<std::size_t>(g_.index(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1)))];
      inside += val[static_cast<std::size_t>(c)] < 0.0 ? 1 : 0;  // f = 0 counts as outside
    }
    if (inside == 0 || inside == 8) return;
    for (const auto& tet : kTets) {
      std::array<int, 4> in, out;
      int ni = 0, no = 0;
      for (int c : tet) (val[static_cast<std::size_t>(c)] < 0.0 ? in[static_cast<std::size_t>(ni++)] : out[static_cast<std::size_t>(no++)]) = c;
      if (ni == 0 || no == 0) continue;
      Vec3 cin = Vec3::Zero(), cout = Vec3::Zero();
      for (int s = 0; s < ni; ++s) cin += corner(in[static_cast<std::size_t>(s)]) / ni;
      for (int s = 0; s < no; ++s) cout += corner(out[static_cast<std::size_t>(s)]) / no;
      const Vec3 dir = cout - cin;
      if (ni == 1 || no == 1) {
        const int lone = ni == 1 ? in[0] : out[0];
        const auto& others = ni == 1 ? out : in;
        triangle(i, j, k, {{{lone, others[0]}, {lone, others[1]}, {lone, others[2]}}}, dir);
        continue;
      }
      // Two in (a, b), two out (c, d): the quad a-c, a-d, b-d, b-c, cut along its shorter diagonal.
      const int a = in[0], b = in[1], c = out[0], d = out[1];
      const auto point = [&](int p, int q) { return linear_point(vertices[static_cast<std::size_t>(vertex(i, j, k, p, q))]); };
      if ((point(a, c) - point(b, d)).squaredNorm() <= (point(a, d) - point(b, c)).squaredNorm()) {
        triangle(i, j, k, {{{a, c}, {a, d}, {b, d}}}, dir);
        triangle(i, j, k, {{{a, c}, {b, d}, {b, c}}}, dir);
      } else {
        triangle(i, j, k, {{{a, d}, {b, d}, {b, c}}}, dir);
        triangle(i, j, k, {{{a, d}, {b, c}, {a, c}}}, dir);
      }
    }
  }

  const Grid& g_;
  const std::vector<double>& values_;
  std::unordered_map<std::uint64_t, int> index_;
};

/// f = 0 on the segment between two samples of opposite sign: regula falsi with the Illinois
/// modification (superlinear, never leaves the bracket, so the vertex stays on its edge).
Vec3 edge_root(const ImplicitFunction& f, const EdgeVertex& e) {
  double t0 = 0.0, t1 = 1.0, v0 = e.va, v1 = e.vb;
  double t = v0 / (v0 - v1);
  int side = 0;
  for (int it = 0; it < 8; ++it) {
    const double v = f.value(e.pa + t * (e.pb - e.pa));
    if (!std::isfinite(v) || v == 0.0) break;
    if ((v < 0.0) == (v0 < 0.0)) {
      t0 = t;
      v0 = v;
      if (side == -1) v1 *= 0.5;
      side = -1;
    } else {
      t1 = t;
      v1 = v;
      if (side == 1) v0 *= 0.5;
      side = 1;
    }
    if (t1 - t0 < 1e-12) break;
    t = (t0 * v1 - t1 * v0) / (v1 - v0);
  }
  // The root of the true f may lie nearer a node than the adjusted samples say (see
  // keep_samples_off_zero): keep the same margin.
  t = std::clamp(t, kEdgeClamp, 1.0 - kEdgeClamp);
  return e.pa + t * (e.pb - e.pa);
}

/// Loops of boundary edges (edges of one face), counted as connected groups of boundary vertices.
std::size_t boundary_loops(const TriangleMesh& mesh) {
  const MeshEdges edges = mesh_edges(mesh, "marching_cubes");
  UnionFind loops(mesh.vertices.size());
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (edges.boundary(e)) loops.unite(edges.ends[e][0], edges.ends[e][1]);
  const std::vector<char> on = edges.boundary_vertices(mesh.vertices.size());
  std::size_t count = 0;
  for (std::size_t v = 0; v < on.size(); ++v) count += on[v] && loops.find(v) == v ? 1 : 0;
  return count;
}

/// The nodes whose exact value the mesh depends on, given a test that certifies f > 0 (empty: all of
/// them, returned as an empty vector). A certified node is outside whatever its value, so only
/// uncertified nodes (U) can be inside, and every grid edge with a vertex on it has an end in U. The
/// vertices read the values at both ends of such edges — U and its 26 neighbours (N) — after
/// keep_samples_off_zero, which reads each node's 6 neighbours: so U, N and their 6 neighbours are
/// needed. Elsewhere any positive value (1) gives the same mesh, bit for bit.
std::vector<char> needed_samples(const Grid& g, const std::function<bool(const Vec3&)>& certified_positive) {
  if (!certified_positive) return {};
  const std::size_t nodes = static_cast<std::size_t>(g.nodes());
  std::vector<char> uncertain(nodes), near(nodes), needed(nodes);
#pragma omp parallel for schedule(dynamic, 1)
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        uncertain[static_cast<std::size_t>(g.index(i, j, k))] = !certified_positive(g.position(i, j, k));
  // Gathers (each node reads its neighbours, writes itself): race-free in parallel.
  const auto dilate = [&g](const std::vector<char>& in, std::vector<char>& out, bool cube) {
#pragma omp parallel for schedule(dynamic, 1)
    for (int k = 0; k < g.nz; ++k)
      for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
          char any = 0;
          for (int dk = -1; dk <= 1 && !any; ++dk)
            for (int dj = -1; dj <= 1 && !any; ++dj)
              for (int di = -1; di <= 1 && !any; ++di) {
                if (!cube && std::abs(di) + std::abs(dj) + std::abs(dk) > 1) continue;
                const int a = i + di, b = j + dj, c = k + dk;
                if (a < 0 || b < 0 || c < 0 || a >= g.nx || b >= g.ny || c >= g.nz) continue;
                any = in[static_cast<std::size_t>(g.index(a, b, c))];
              }
          out[static_cast<std::size_t>(g.index(i, j, k))] = any;
        }
  };
  dilate(uncertain, near, true);
  dilate(near, needed, false);
  return needed;
}

void keep_samples_off_zero(const Grid& g, std::vector<double>& values) {
  std::vector<double> out(values);
#pragma omp parallel for schedule(dynamic, 1)
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const double v = values[static_cast<std::size_t>(g.index(i, j, k))];
        double spread = 0.0;
        const int nb[6][3] = {{i - 1, j, k}, {i + 1, j, k}, {i, j - 1, k}, {i, j + 1, k}, {i, j, k - 1}, {i, j, k + 1}};
        for (const auto& n : nb)
          if (n[0] >= 0 && n[1] >= 0 && n[2] >= 0 && n[0] < g.nx && n[1] < g.ny && n[2] < g.nz)
            spread = std::max(spread, std::abs(values[static_cast<std::size_t>(g.index(n[0], n[1], n[2]))] - v));
        if (std::abs(v) < kOffZero * spread) out[static_cast<std::size_t>(g.index(i, j, k))] = kOffZero * spread;
      }
  values.swap(out);
}

}  // namespace

PolygonizeResult marching_cubes(const ImplicitFunction& f, const std::vector<Vec3>& data,
                                const MarchingCubesOptions& options) {
  options.check();
  const Stopwatch clock;
  const double h = options.step;
  BoundingBox box = f.domain();
  if (options.region == "data" && !data.empty()) {
    box = bounding_box(data);
    box.min -= Vec3::Constant(options.margin);
    box.max += Vec3::Constant(options.margin);
  }
  const Grid g = make_grid(box, h, options.max_grid_nodes);

  // 1. Samples (the expensive part for a T-spline: one evaluation per node, in parallel), skipping
  // the nodes whose exact value cannot matter (needed_samples).
  const std::vector<char> needed = needed_samples(g, f.positive_certificate());
  std::vector<double> values(static_cast<std::size_t>(g.nodes()), 1.0);
  long evaluated = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : evaluated)
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const std::size_t n = static_cast<std::size_t>(g.index(i, j, k));
        if (!needed.empty() && !needed[n]) continue;
        const double v = f.value(g.position(i, j, k));
        values[n] = std::isfinite(v) ? v : 1.0;  // undefined: outside
        ++evaluated;
      }
  const double sample_seconds = clock.seconds();
  keep_samples_off_zero(g, values);

  // 2. Triangles, vertices shared by grid edge.
  Extractor ex(g, values);
  ex.run();
  if (ex.faces.empty())
    throw AlgorithmError("marching_cubes: f does not change sign on the grid of step " + std::to_string(h) +
                         " (no level set inside the region, or one thinner than the step)");

  // 3. Vertex placement, optional Newton projection, normals from grad f (all per vertex, parallel).
  TriangleMesh mesh;
  mesh.vertices.resize(ex.vertices.size());
  mesh.normals.resize(ex.vertices.size());
  mesh.faces = std::move(ex.faces);
  NewtonOptions newton = options.newton();
  newton.max_step = 0.5 * h;  // a vertex is within ~h of the surface; longer steps mean a run-off
  const bool root = options.vertex_placement == "root";
  const long nv = static_cast<long>(ex.vertices.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (long v = 0; v < nv; ++v) {
    const EdgeVertex& e = ex.vertices[static_cast<std::size_t>(v)];
    Vec3 p = root ? edge_root(f, e) : e.pa + std::clamp(e.va / (e.va - e.vb), kEdgeClamp, 1.0 - kEdgeClamp) * (e.pb - e.pa);
    Vec3 grad;
    if (options.newton_project) {
      const NewtonProjection r = newton_project(f, p, newton);
      if (r.converged() && (r.point - p).norm() <= h) p = r.point;
    }
    f.evaluate(p, &grad);
    mesh.vertices[static_cast<std::size_t>(v)] = p;
    mesh.normals[static_cast<std::size_t>(v)] = grad.normalized();
  }
  // A critical point of f on the surface has no gradient direction: fall back to the area-weighted
  // normal of the triangles around the vertex there.
  std::vector<char> bad(mesh.vertices.size(), 0);
  bool any_bad = false;
  for (std::size_t v = 0; v < mesh.normals.size(); ++v)
    if (!mesh.normals[v].allFinite() || mesh.normals[v].squaredNorm() < 0.5) {
      bad[v] = 1;
      any_bad = true;
      mesh.normals[v] = Vec3::Zero();
    }
  if (any_bad) {
    for (const Face& t : mesh.faces) {
      const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
      const Vec3 n = (mesh.vertices[static_cast<std::size_t>(t[1])] - a).cross(mesh.vertices[static_cast<std::size_t>(t[2])] - a);
      for (int v : t)
        if (bad[static_cast<std::size_t>(v)]) mesh.normals[static_cast<std::size_t>(v)] += n;
    }
    for (std::size_t v = 0; v < mesh.normals.size(); ++v)
      if (bad[v]) mesh.normals[v] = mesh.normals[v].squaredNorm() > 0.0 ? mesh.normals[v].normalized() : Vec3::UnitZ();
  }

  // 4. Components: with data, keep those a foot point lies on (the seeding rule of §2.2).
  const VertexComponents components = vertex_components(mesh);
  const std::vector<int>& label = components.label;
  const std::size_t found = components.count;
  std::vector<char> keep(found, 1);
  SeedCandidates feet;
  if (!data.empty() && options.drop_dataless_components) {
    feet = foot_point_seeds(f, data, options.newton());
    keep.assign(found, 0);
    const MeshProximity near(mesh, 2.0 * h);
    for (const Vec3& q : feet.points) {
      const MeshProximity::Hit hit = near.closest(q);
      if (hit.face >= 0 && hit.distance <= options.cover_distance * h)
        keep[static_cast<std::size_t>(label[static_cast<std::size_t>(mesh.faces[static_cast<std::size_t>(hit.face)][0])])] = 1;
    }
  }
  const std::size_t kept = static_cast<std::size_t>(std::count(keep.begin(), keep.end(), 1));
  if (kept == 0)
    throw AlgorithmError("marching_cubes: none of the " + std::to_string(found) +
                         " components of the level set carries a data foot point");
  if (kept < found) {
    std::vector<int> remap(mesh.vertices.size(), -1);
    TriangleMesh out;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
      if (label[v] >= 0 && keep[static_cast<std::size_t>(label[v])]) {
        remap[v] = static_cast<int>(out.vertices.size());
        out.vertices.push_back(mesh.vertices[v]);
        out.normals.push_back(mesh.normals[v]);
      }
    for (const Face& t : mesh.faces)
      if (remap[static_cast<std::size_t>(t[0])] >= 0)
        out.faces.push_back({{remap[static_cast<std::size_t>(t[0])], remap[static_cast<std::size_t>(t[1])], remap[static_cast<std::size_t>(t[2])]}});
    mesh = std::move(out);
  }

  PolygonizeResult result;
  result.mesh = std::move(mesh);
  PolygonizeSummary& s = result.summary;
  s.method = "marching_cubes";
  s.vertices = result.mesh.vertices.size();
  s.faces = result.mesh.faces.size();
  s.components = kept;
  s.dropped_components = found - kept;
  s.seed_candidates = feet.candidates;
  s.seed_failures = feet.failures;
  s.seeds_outside_domain = feet.outside_domain;
  s.open_boundaries = boundary_loops(result.mesh);
  s.seconds = clock.seconds();
  s.quality = mesh_quality(result.mesh);
  s.details = {{"step", h},
               {"grid", {g.nx, g.ny, g.nz}},
               {"region", options.region},
               {"vertex_placement", options.vertex_placement},
               {"newton_project", options.newton_project},
               {"sample_seconds", sample_seconds},
               {"samples_evaluated", evaluated}};
  return result;
}

}  // namespace dtsl
