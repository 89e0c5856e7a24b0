// Hartmann's marching method (The Visual Computer 14:95-108, 1998), as the paper uses it (§2.2).
//
// One march (march_component):
//   1. project the seed onto f = 0; six points at distance delta in its tangent plane, projected, give
//      the first hexagon of six triangles and the first front polygon;
//   2. repeatedly take the front point p_m of smallest front angle w (over all fronts) and
//      a. if its front has three points, close it with one triangle;
//      b. distance check (Hartmann's step 2): if a front point p_j closer than delta (not a near
//         neighbour of p_m on its front) lies in p_m's free sector and p_m in p_j's, join them by an
//         edge: the front splits in two (same front) or two fronts merge (different fronts);
//      c. otherwise create n_t = floor(3 w / pi) + 1 triangles at p_m, with Hartmann's corrections
//         (fewer triangles when w / n_t < 0.8 rad, two when one would leave a long edge, one when a
//         neighbour is closer than delta / 2); the n_t - 1 new points are made in p_m's tangent plane
//         at distance delta, equally spaced in angle, and projected onto f = 0 by Newton (ours: one
//         that does not land within 0.5-1.6 delta, its normal within 60 degrees, is made at delta / 2,
//         / 4 or / 8 instead; a component that needs that at more than 1 % of its points, or that
//         then covers itself twice, is refused); each new point gets the distance check of b at
//         once (ours: without it, on thin tubes at coarse steps a front could grow over another before
//         the new point's turn came);
//   3. until no front is left (or only fronts whose points all lie outside f's domain).
// Taking the smallest angle first keeps the front convex-ish and the triangles near-equilateral;
// the distance check is what lets fronts meet without overlapping (and what lets the mesh acquire
// handles: a torus needs one split and one merge).
#include "algorithms/polygonize/marching_triangulation.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <queue>
#include <sstream>
#include <unordered_set>

#include "algorithms/polygonize/front.hpp"
#include "algorithms/polygonize/overlapping_sheets.hpp"
#include "algorithms/polygonize/spatial_hash.hpp"
#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"

namespace dtsl {

namespace {
// Halved steps mend a spot too curved for the step. Where more than this share of a component's points
// need one, the step is too large for the surface itself (a tube thinner than the step closes on itself
// in a few dozen points), and the caller must reduce it everywhere.
constexpr double kMaxHalfStepShare = 0.01;
// How many times a new point's step is halved at its spot (the pipeline halves the whole step as often).
constexpr int kLocalStepHalvings = 3;
// Two vertices closer than this x the step, facing the same way, more than kOverlapHops edges apart along
// the mesh: a second sheet (overlapping_sheets.hpp). Within a patch of eighth steps half a step is 4 edges.
constexpr double kOverlapRadius = 0.5;
constexpr int kOverlapHops = 8;
}  // namespace

void MarchingTriangulationOptions::visit(FieldVisitor& v) {
  v.field("step", step,
          "marching step delta in the [-1,1] frame: the target edge length (paper: 0.2 l_T); must stay well "
          "below the smallest curvature radius");
  v.field("join_distance", join_distance,
          "Hartmann's distance check, x step: front points closer than this are joined (front split or merge)");
  v.field("cover_distance", cover_distance,
          "seeding step 5, x step: a data foot point this close to a finished component's mesh is covered");
  v.field("seed_grid_step", seed_grid_step,
          "grid spacing for seeds from sign changes of f when no data points are given (frame units)");
  v.field("max_components", max_components, "cap on meshed components (more: AlgorithmError)");
  v.field("max_triangles", max_triangles, "cap on the triangles of one component (reached: AlgorithmError)");
  v.field("newton_tolerance", newton_tolerance, "Newton projection onto f = 0: stop when |f|/|grad f| is below this");
  v.field("newton_max_iterations", newton_max_iterations, "Newton projection: iteration cap");
}

void MarchingTriangulationOptions::check() const {
  check_range("step", step, 1e-5, 0.5);
  check_range("join_distance", join_distance, 0.5, 1.5);
  check_range("cover_distance", cover_distance, 0.01, 1.0);
  check_range("seed_grid_step", seed_grid_step, 1e-3, 1.0);
  check_range("max_components", max_components, 1, 100'000'000);
  check_range("max_triangles", max_triangles, 6, 2'000'000'000);
  newton().check();
}

NewtonOptions MarchingTriangulationOptions::newton() const {
  NewtonOptions n;
  n.tolerance = newton_tolerance;
  n.max_iterations = newton_max_iterations;
  return n;
}

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;

std::string format_point(const Vec3& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

std::uint64_t undirected(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}
std::uint64_t directed(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

/// A unit vector orthogonal to n.
Vec3 any_orthogonal(const Vec3& n) {
  const Vec3 axis = std::abs(n.x()) < 0.6 ? Vec3::UnitX() : (std::abs(n.y()) < 0.6 ? Vec3::UnitY() : Vec3::UnitZ());
  return (axis - axis.dot(n) * n).normalized();
}

class Marcher {
 public:
  Marcher(const ImplicitFunction& f, const MarchingTriangulationOptions& o, MarchStatistics& s)
      : f_(f), o_(o), stats_(s), delta_(o.step), join_(o.join_distance * o.step), hash_(join_),
        domain_(f.domain()) {
    newton_ = o.newton();
    // New points start within ~delta^2 kappa / 2 of the surface; a longer step means Newton is
    // running off (small |grad f|), and clamping keeps it on the sheet it started near.
    newton_.max_step = 0.5 * delta_;
  }

  ComponentMesh run(const Vec3& seed);

 private:
  struct Entry {
    double angle;
    int node, version;
    bool operator<(const Entry& o) const {  // priority_queue pops the largest: invert for smallest angle
      return angle != o.angle ? angle > o.angle : node > o.node;
    }
  };

  const Vec3& pos(int node) const { return V_[static_cast<std::size_t>(fronts_.node(node).vertex)]; }
  const Vec3& nrm(int node) const { return N_[static_cast<std::size_t>(fronts_.node(node).vertex)]; }

  bool project(const Vec3& guess, NewtonProjection& r) {
    r = newton_project(f_, guess, newton_);
    stats_.newton_iterations += static_cast<std::size_t>(r.iterations);
    return r.converged();
  }
  /// A new point projected from `step` away from a front point (normal n) landed where the march can
  /// use it: `distance` from the front point between half and 1.6 steps, its normal within 60 degrees of n.
  static bool lands(const NewtonProjection& r, const Vec3& n, double distance, double step) {
    return distance >= 0.5 * step && distance <= 1.6 * step && r.normal().dot(n) >= 0.5;
  }
  int add_vertex(const NewtonProjection& r) {
    V_.push_back(r.point);
    N_.push_back(r.normal());
    outside_.push_back(!((r.point.array() >= domain_.min.array()).all() && (r.point.array() <= domain_.max.array()).all()));
    return static_cast<int>(V_.size()) - 1;
  }
  void add_face(int a, int b, int c);
  void add_node(int node) {
    FrontNode& n = fronts_.node(node);
    n.frozen = outside_[static_cast<std::size_t>(n.vertex)];
    hash_.insert(node, pos(node));
  }
  void drop_node(int node) { hash_.remove(node, pos(node)); }

  /// Angle at `node` of direction x - p, counter-clockwise about the normal from the direction of
  /// prev(node), all in the tangent plane: in [0, 2 pi).
  double sector_angle(int node, const Vec3& x) const;
  double front_angle(int node) const;
  void refresh(int node);
  bool in_sector(int node, const Vec3& x) const;

  int find_partner(int m) const;
  void join(int m, int j);
  void close_triangle(int m);
  void close_slit(int m);
  void expand(int m);

  const ImplicitFunction& f_;
  const MarchingTriangulationOptions& o_;
  MarchStatistics& stats_;
  NewtonOptions newton_;
  double delta_, join_;
  SpatialHash hash_;  // live front nodes by position
  BoundingBox domain_;

  std::vector<Vec3> V_, N_;
  std::vector<char> outside_;
  std::vector<Face> F_;
  std::unordered_set<std::uint64_t> edges_;           // every edge made (triangle sides and joins)
  std::unordered_set<std::uint64_t> directed_edges_;  // triangle sides as oriented: each at most once
  FrontSet fronts_;
  std::priority_queue<Entry> heap_;
};

void Marcher::add_face(int a, int b, int c) {
  if (a == b || b == c || c == a)
    throw AlgorithmError("marching_triangulation: internal error: degenerate triangle near " + format_point(V_[static_cast<std::size_t>(a)]));
  for (const auto& e : {std::pair<int, int>{a, b}, {b, c}, {c, a}}) {
    // A second triangle on the same oriented edge means two fronts overlapped: the surface is
    // too curved or too thin for the step here. Report rather than return a non-manifold mesh.
    if (!directed_edges_.insert(directed(e.first, e.second)).second)
      throw AlgorithmError("marching_triangulation: fronts overlapped near " + format_point(V_[static_cast<std::size_t>(e.first)]) +
                           " (an edge got a third triangle); reduce 'step' (" + std::to_string(delta_) + ")");
    edges_.insert(undirected(e.first, e.second));
  }
  F_.push_back({{a, b, c}});
}

double Marcher::sector_angle(int node, const Vec3& x) const {
  const Vec3& p = pos(node);
  const Vec3& n = nrm(node);
  Vec3 a = pos(fronts_.node(node).prev) - p, d = x - p;
  a -= a.dot(n) * n;
  d -= d.dot(n) * n;
  double w = std::atan2(n.dot(a.cross(d)), a.dot(d));
  if (w < 0.0) w += kTwoPi;
  return w;
}

double Marcher::front_angle(int node) const {
  const FrontNode& nd = fronts_.node(node);
  if (fronts_.node(nd.prev).vertex == fronts_.node(nd.next).vertex) return 0.0;  // the tip of a slit
  return sector_angle(node, pos(nd.next));
}

void Marcher::refresh(int node) {
  FrontNode& nd = fronts_.node(node);
  nd.angle = front_angle(node);
  ++nd.version;
  if (!nd.frozen) heap_.push({nd.angle, node, nd.version});
}

bool Marcher::in_sector(int node, const Vec3& x) const {
  // A margin keeps joins away from the front edges at the node: a chord that hugs an edge would cut
  // a sliver off, and the front point on that edge will be handled by its own expansion instead.
  constexpr double margin = 0.15;
  const double t = sector_angle(node, x);
  return t > margin && t < fronts_.node(node).angle - margin;
}

int Marcher::find_partner(int m) const {
  const FrontNode& M = fronts_.node(m);
  const FrontNode& P = fronts_.node(M.prev);
  const FrontNode& Q = fronts_.node(M.next);
  const int vm = M.vertex;
  // Near neighbours along the front are handled by the angle rule, not by joins.
  const int excluded[5] = {vm, P.vertex, Q.vertex, fronts_.node(P.prev).vertex, fronts_.node(Q.next).vertex};
  const Vec3& pm = V_[static_cast<std::size_t>(vm)];
  const Vec3& nm = N_[static_cast<std::size_t>(vm)];
  int best = -1;
  double best_d2 = join_ * join_;
  hash_.for_each_near(pm, join_, [&](int j) {
    const FrontNode& J = fronts_.node(j);
    if (!J.alive) return;
    for (int e : excluded)
      if (J.vertex == e) return;
    const Vec3& pj = V_[static_cast<std::size_t>(J.vertex)];
    const double d2 = (pj - pm).squaredNorm();
    if (d2 >= best_d2) return;
    // The other side of a thin part of the surface faces away: never join across it.
    if (N_[static_cast<std::size_t>(J.vertex)].dot(nm) <= 0.0) return;
    if (edges_.count(undirected(vm, J.vertex))) return;
    if (!in_sector(m, pj) || !in_sector(j, pm)) return;
    best = j;
    best_d2 = d2;
  });
  return best;
}

void Marcher::join(int m, int j) {
  const bool same = fronts_.node(m).front == fronts_.node(j).front;
  const auto copies = same ? fronts_.split(m, j) : fronts_.merge(m, j);
  ++(same ? stats_.splits : stats_.merges);
  edges_.insert(undirected(fronts_.node(m).vertex, fronts_.node(j).vertex));
  add_node(copies.first);
  add_node(copies.second);
  for (int n : {m, j, copies.first, copies.second}) refresh(n);
}

void Marcher::close_triangle(int m) {
  const FrontNode& M = fronts_.node(m);
  const int f = M.front, a = fronts_.node(M.prev).vertex, b = fronts_.node(M.next).vertex;
  add_face(M.vertex, a, b);
  for (int n : fronts_.nodes_of(f)) drop_node(n);
  fronts_.remove_front(f);
}

void Marcher::close_slit(int m) {
  // prev(m) and next(m) are copies of one vertex u: the edges u-m on both sides already have their
  // two triangles, so the front simply closes up over them.
  const int n = fronts_.node(m).next, p = fronts_.node(m).prev;
  drop_node(m);
  drop_node(n);
  fronts_.replace(m, {});
  fronts_.replace(n, {});
  ++stats_.slits_closed;
  const int f = fronts_.node(p).front;
  if (fronts_.front_size(f) <= 2) {  // p -> x -> p: the last two edges close up as well
    for (int k : fronts_.nodes_of(f)) drop_node(k);
    fronts_.remove_front(f);
    return;
  }
  refresh(p);
  refresh(fronts_.node(p).next);
}

void Marcher::expand(int m) {
  const FrontNode M = fronts_.node(m);  // a copy: replace() below invalidates references
  const int p = M.prev, q = M.next;
  const int vm = M.vertex, vp = fronts_.node(p).vertex, vq = fronts_.node(q).vertex;
  if (vp == vq) {
    close_slit(m);
    return;
  }
  const Vec3 pm = V_[static_cast<std::size_t>(vm)], nm = N_[static_cast<std::size_t>(vm)];
  const double w = M.angle;
  // Hartmann's rule for the number of new triangles and its corrections.
  int nt = static_cast<int>(std::floor(3.0 * w / kPi)) + 1;
  double dw = w / nt;
  if (dw < 0.8 && nt > 1) {
    --nt;
    dw = w / nt;
  }
  if (nt == 1 && dw > 0.8 && (V_[static_cast<std::size_t>(vp)] - V_[static_cast<std::size_t>(vq)]).norm() > 1.2 * delta_) {
    nt = 2;
    dw = w / 2;
  }
  if (w < 3.0 && ((V_[static_cast<std::size_t>(vp)] - pm).norm() <= 0.5 * delta_ ||
                  (V_[static_cast<std::size_t>(vq)] - pm).norm() <= 0.5 * delta_))
    nt = 1;

  if (nt == 1) {
    add_face(vm, vp, vq);
    drop_node(m);
    fronts_.replace(m, {});
    refresh(p);
    refresh(q);
    return;
  }
  Vec3 e1 = V_[static_cast<std::size_t>(vp)] - pm;
  e1 -= e1.dot(nm) * nm;
  e1.normalize();
  const Vec3 e2 = nm.cross(e1);
  std::vector<int> chain;  // prev, new points..., next
  chain.push_back(vp);
  for (int k = 1; k < nt; ++k) {
    const double t = k * dw;
    const Vec3 direction = std::cos(t) * e1 + std::sin(t) * e2;
    NewtonProjection r;
    const bool ok = project(pm + delta_ * direction, r);
    const double dist = (r.point - pm).norm();
    if (!(ok && lands(r, nm, dist, delta_))) {
      // One spot too curved for the step: a point at a half, a quarter or an eighth of the step there, a
      // locally finer patch, before the caller halves the step everywhere (4x the vertices per halving).
      NewtonProjection near;
      double sub = delta_;
      bool landed = false;
      for (int halving = 0; halving < kLocalStepHalvings && !landed; ++halving) {
        sub *= 0.5;
        landed = project(pm + sub * direction, near) && lands(near, nm, (near.point - pm).norm(), sub);
      }
      if (!landed)
        throw AlgorithmError("marching_triangulation: the step " + std::to_string(delta_) +
                             " is too large for the surface near " + format_point(pm) + " (a new point " +
                             (ok ? "projected " + std::to_string(dist / delta_) + " steps away or turned its normal"
                                 : std::string("failed to project: ") + to_string(r.status)) +
                             ", and at 1/2, 1/4 and 1/8 of the step too); reduce 'step'");
      r = near;
      ++stats_.half_steps;
    }
    chain.push_back(add_vertex(r));
  }
  chain.push_back(vq);
  for (std::size_t k = 0; k + 1 < chain.size(); ++k) add_face(vm, chain[k], chain[k + 1]);
  drop_node(m);
  const std::vector<int> created = fronts_.replace(m, std::vector<int>(chain.begin() + 1, chain.end() - 1));
  for (int n : created) add_node(n);
  refresh(p);
  for (int n : created) refresh(n);
  refresh(q);
  // Distance check of the new points right away (Hartmann checks new points as they are made): a new
  // point that landed near another part of the front must be joined before anything else grows
  // there, or fronts advance over each other.
  for (int n : created) {
    if (!fronts_.node(n).alive) continue;
    const int j = find_partner(n);
    if (j >= 0) join(n, j);
  }
}

ComponentMesh Marcher::run(const Vec3& seed) {
  ComponentMesh out;
  NewtonProjection s;
  if (!project(seed, s)) {
    out.skipped = true;
    return out;
  }
  const Vec3 n0 = s.normal();
  const Vec3 e1 = any_orthogonal(n0), e2 = n0.cross(e1);
  // The first hexagon (Hartmann §3, step 1). If its points do not land about delta away with
  // similar normals, the component is too small or too curved for this step: skip the seed.
  std::vector<NewtonProjection> hex(6);
  for (int k = 0; k < 6; ++k) {
    const double t = k * kPi / 3.0;
    const bool ok = project(s.point + delta_ * (std::cos(t) * e1 + std::sin(t) * e2), hex[static_cast<std::size_t>(k)]);
    const double dist = (hex[static_cast<std::size_t>(k)].point - s.point).norm();
    if (!ok || dist < 0.5 * delta_ || dist > 1.5 * delta_ || hex[static_cast<std::size_t>(k)].normal().dot(n0) < 0.5) {
      out.skipped = true;
      return out;
    }
  }
  const int c = add_vertex(s);
  std::vector<int> ring;
  for (const NewtonProjection& h : hex) ring.push_back(add_vertex(h));
  for (int k = 0; k < 6; ++k) add_face(c, ring[static_cast<std::size_t>(k)], ring[static_cast<std::size_t>((k + 1) % 6)]);
  const int front = fronts_.create_front(ring);
  const std::vector<int> first = fronts_.nodes_of(front);
  for (int n : first) add_node(n);
  for (int n : first) refresh(n);

  const std::size_t max_faces = static_cast<std::size_t>(o_.max_triangles);
  std::size_t iterations = 0;
  const std::size_t max_iterations = 4 * max_faces + 1000;  // each step adds a face or a new edge
  while (!heap_.empty()) {
    const Entry e = heap_.top();
    heap_.pop();
    const FrontNode& nd = fronts_.node(e.node);
    if (!nd.alive || nd.frozen || nd.version != e.version) continue;
    if (++iterations > max_iterations || F_.size() > max_faces)
      throw AlgorithmError("marching_triangulation: the front did not close after " + std::to_string(F_.size()) +
                           " triangles (max_triangles = " + std::to_string(o_.max_triangles) + ") near " +
                           format_point(pos(e.node)));
    if (fronts_.front_size(nd.front) == 3) {
      close_triangle(e.node);
      continue;
    }
    const int j = find_partner(e.node);
    if (j >= 0) {
      join(e.node, j);
      continue;
    }
    expand(e.node);
  }
  stats_.open_boundaries += static_cast<std::size_t>(fronts_.alive_front_count());

  out.mesh.vertices = std::move(V_);
  out.mesh.normals = std::move(N_);
  out.mesh.faces = std::move(F_);
  return out;
}

}  // namespace

ComponentMesh march_component(const ImplicitFunction& f, const Vec3& seed, const MarchingTriangulationOptions& options,
                              MarchStatistics& statistics) {
  const std::size_t half_steps_before = statistics.half_steps;
  Marcher marcher(f, options, statistics);
  ComponentMesh component = marcher.run(seed);
  const std::size_t half_steps = statistics.half_steps - half_steps_before;
  if (static_cast<double>(half_steps) > kMaxHalfStepShare * static_cast<double>(component.mesh.vertices.size()))
    throw AlgorithmError("marching_triangulation: the step " + std::to_string(options.step) +
                         " is too large for the surface: " + std::to_string(half_steps) + " of the " +
                         std::to_string(component.mesh.vertices.size()) +
                         " points of a component needed a halved step; reduce 'step'");
  // Past a part thinner than the step, a front can grow over the finished mesh unseen.
  if (half_steps > 0)
    if (const std::optional<Vec3> at = overlapping_sheets(component.mesh, kOverlapRadius * options.step, kOverlapHops))
      throw AlgorithmError("marching_triangulation: the step " + std::to_string(options.step) +
                           " is too large for the surface: after halved steps the mesh covers itself twice near " +
                           format_point(*at) + "; reduce 'step'");
  return component;
}

PolygonizeResult marching_triangulation(const ImplicitFunction& f, const std::vector<Vec3>& data,
                                        const MarchingTriangulationOptions& options) {
  options.check();
  const Stopwatch clock;
  const NewtonOptions newton = options.newton();
  const SeedCandidates seeds = data.empty() ? grid_seeds(f, f.domain(), options.seed_grid_step, newton)
                                            : foot_point_seeds(f, data, newton);
  if (seeds.points.empty())
    throw AlgorithmError("marching_triangulation: no seed on f = 0 (" + std::to_string(seeds.candidates) +
                         (data.empty() ? " grid roots" : " data points") + ", " + std::to_string(seeds.failures) +
                         " Newton failures, " + std::to_string(seeds.outside_domain) + " outside the domain)");
  MarchStatistics stats;
  const double delta = options.step;
  SeededMeshing seeded = mesh_from_seeds(
      seeds.points, options.cover_distance * delta, 2.0 * delta, 2.0 * delta,
      static_cast<std::size_t>(options.max_components),
      [&](const Vec3& seed) { return march_component(f, seed, options, stats); });

  if (seeded.components == 0)
    throw AlgorithmError("marching_triangulation: no component could be started from " +
                         std::to_string(seeds.points.size()) + " seeds: the level set is smaller or more curved than "
                         "the step " + std::to_string(delta) + "; reduce 'step'");
  PolygonizeResult result;
  result.mesh = std::move(seeded.mesh);
  PolygonizeSummary& s = result.summary;
  s.method = "marching_triangulation";
  s.vertices = result.mesh.vertices.size();
  s.faces = result.mesh.faces.size();
  s.components = seeded.components;
  s.seed_candidates = seeds.candidates;
  s.seed_failures = seeds.failures;
  s.seeds_outside_domain = seeds.outside_domain;
  s.dropped_components = seeded.skipped_seeds;
  s.open_boundaries = stats.open_boundaries;
  s.seconds = clock.seconds();
  s.quality = mesh_quality(result.mesh);
  s.details = {{"step", delta},
               {"seeds_from", data.empty() ? "grid" : "data"},
               {"skipped_seeds", seeded.skipped_seeds},
               {"duplicate_marches", seeded.duplicates},
               {"splits", stats.splits},
               {"merges", stats.merges},
               {"slits_closed", stats.slits_closed},
               {"half_steps", stats.half_steps},
               {"newton_iterations_per_vertex",
                s.vertices ? static_cast<double>(stats.newton_iterations) / static_cast<double>(s.vertices) : 0.0}};
  return result;
}

}  // namespace dtsl
