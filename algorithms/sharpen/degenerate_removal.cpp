#include "algorithms/sharpen/degenerate_removal.hpp"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>

#include <cmath>
#include <string>

#include "framework/core/error.hpp"

namespace dtsl::sharpen {

void DegenerateRemovalOptions::visit(FieldVisitor& v) {
  v.field("min_edge_ratio", min_edge_ratio, "collapse edges shorter than this x the mean edge length (0: off)");
  v.field("min_angle_deg", min_angle_deg,
          "also collapse the shortest edge of triangles with a smaller angle (degrees; 0: off)");
  v.field("max_passes", max_passes, "passes over the mesh");
}

void DegenerateRemovalOptions::check() const {
  check_range("min_edge_ratio", min_edge_ratio, 0.0, 1.0);
  check_range("min_angle_deg", min_angle_deg, 0.0, 60.0);
  check_range("max_passes", max_passes, 0, 100);
}

namespace {

using K = CGAL::Simple_cartesian<double>;
using SM = CGAL::Surface_mesh<K::Point_3>;
using VI = SM::Vertex_index;
using HI = SM::Halfedge_index;

Vec3 pos(const SM& sm, VI v) {
  const auto& p = sm.point(v);
  return Vec3(p.x(), p.y(), p.z());
}

Vec3 face_cross(const SM& sm, SM::Face_index f, VI moved, const Vec3& at) {
  Vec3 p[3];
  int i = 0;
  for (VI v : CGAL::vertices_around_face(sm.halfedge(f), sm)) p[i++] = v == moved ? at : pos(sm, v);
  return (p[1] - p[0]).cross(p[2] - p[0]);
}

double smallest_angle_deg(const SM& sm, SM::Face_index f, HI* shortest) {
  HI h = sm.halfedge(f);
  Vec3 p[3];
  HI hs[3];
  for (int i = 0; i < 3; ++i, h = sm.next(h)) {
    hs[i] = h;
    p[i] = pos(sm, sm.source(h));
  }
  double best = 180.0, shortest_len = HUGE_VAL;
  for (int i = 0; i < 3; ++i) {
    const Vec3 a = p[(i + 1) % 3] - p[i], b = p[(i + 2) % 3] - p[i];
    const double na = a.norm(), nb = b.norm();
    if (na < shortest_len) {
      shortest_len = na;
      *shortest = hs[i];  // halfedge p[i] -> p[i+1]
    }
    if (na == 0.0 || nb == 0.0) return 0.0;
    best = std::min(best, std::acos(std::clamp(a.dot(b) / (na * nb), -1.0, 1.0)) * 180.0 / M_PI);
  }
  return best;
}

}  // namespace

DegenerateRemovalReport remove_degenerate_triangles(TriangleMesh& mesh, std::vector<char>& sharp,
                                                    const DegenerateRemovalOptions& o,
                                                    const std::vector<Vec3>& reference_normals) {
  o.check();
  DegenerateRemovalReport rep;
  if (o.max_passes == 0 || (o.min_edge_ratio == 0.0 && o.min_angle_deg == 0.0)) {
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) rep.face_origin.push_back(static_cast<int>(f));
    return rep;
  }
  SM sm;
  for (const auto& v : mesh.vertices) sm.add_vertex(K::Point_3(v.x(), v.y(), v.z()));
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& t = mesh.faces[f];
    if (sm.add_face(VI(t[0]), VI(t[1]), VI(t[2])) == SM::null_face())
      throw AlgorithmError("degenerate removal: face " + std::to_string(f) +
                           " cannot be added to a 2-manifold polygon mesh (non-manifold input)");
  }
  auto sharp_map = sm.add_property_map<VI, char>("v:sharp", 0).first;
  // Faces keep their indices until garbage collection, so the reference normals index directly.
  const bool has_reference = reference_normals.size() == mesh.faces.size();
  for (std::size_t v = 0; v < sharp.size() && v < mesh.vertices.size(); ++v) sharp_map[VI(v)] = sharp[v];

  double mean = 0.0;
  for (auto e : sm.edges()) mean += (pos(sm, sm.source(sm.halfedge(e))) - pos(sm, sm.target(sm.halfedge(e)))).norm();
  mean /= std::max<std::size_t>(1, sm.number_of_edges());
  const double min_len = o.min_edge_ratio * mean;
  // Only the region the evolution moved is repaired; the rest of the mesh is the caller's.
  const bool restrict_to_sharp = !sharp.empty();

  // Collapses h's edge if safe; returns whether it did.
  auto try_collapse = [&](HI h) {
    const VI a = sm.source(h), b = sm.target(h);
    if (!CGAL::Euler::does_satisfy_link_condition(sm.edge(h), sm)) return false;
    Vec3 target = 0.5 * (pos(sm, a) + pos(sm, b));
    if (sharp_map[a] && !sharp_map[b]) target = pos(sm, a);
    if (sharp_map[b] && !sharp_map[a]) target = pos(sm, b);
    // Faces around a and b that survive the collapse must keep their orientation and some area.
    for (VI v : {a, b})
      for (auto f : CGAL::faces_around_target(sm.halfedge(v), sm)) {
        if (f == SM::null_face() || f == sm.face(h) || f == sm.face(sm.opposite(h))) continue;
        const Vec3 before = face_cross(sm, f, v, pos(sm, v));
        const Vec3 after = face_cross(sm, f, v, target);
        if (after.dot(before) <= 0.1 * before.squaredNorm()) return false;
        if (has_reference && after.dot(reference_normals[f.idx()]) <= 0.0) return false;
      }
    const char s = sharp_map[a] || sharp_map[b];
    const VI kept = CGAL::Euler::collapse_edge(sm.edge(h), sm);
    sm.point(kept) = K::Point_3(target.x(), target.y(), target.z());
    sharp_map[kept] = s;
    return true;
  };

  for (int pass = 0; pass < o.max_passes; ++pass) {
    std::size_t done = 0;
    rep.rejected = 0;
    for (auto e : sm.edges()) {
      if (sm.is_removed(e)) continue;
      const HI h = sm.halfedge(e);
      if (restrict_to_sharp && !sharp_map[sm.source(h)] && !sharp_map[sm.target(h)]) continue;
      bool candidate = (pos(sm, sm.source(h)) - pos(sm, sm.target(h))).norm() < min_len;
      if (!candidate && o.min_angle_deg > 0.0) {
        for (HI g : {h, sm.opposite(h)}) {
          if (sm.is_border(g)) continue;
          HI shortest;
          if (smallest_angle_deg(sm, sm.face(g), &shortest) < o.min_angle_deg && sm.edge(shortest) == e) candidate = true;
        }
      }
      if (!candidate) continue;
      if (try_collapse(h)) ++done;
      else ++rep.rejected;
    }
    rep.collapsed += done;
    if (done == 0) break;
  }

  auto origin = sm.add_property_map<SM::Face_index, int>("f:origin", -1).first;
  for (auto f : sm.faces()) origin[f] = static_cast<int>(f.idx());
  sm.collect_garbage();
  sharp_map = sm.property_map<VI, char>("v:sharp").first;
  origin = sm.property_map<SM::Face_index, int>("f:origin").first;
  TriangleMesh out;
  std::vector<char> out_sharp;
  for (VI v : sm.vertices()) {
    out.vertices.push_back(pos(sm, v));
    out_sharp.push_back(sharp_map[v]);
  }
  for (auto f : sm.faces()) {
    Face t;
    int i = 0;
    for (VI v : CGAL::vertices_around_face(sm.halfedge(f), sm)) t[i++] = static_cast<int>(v.idx());
    out.faces.push_back(t);
    rep.face_origin.push_back(origin[f]);
  }
  mesh = std::move(out);
  sharp = std::move(out_sharp);
  return rep;
}

}  // namespace dtsl::sharpen
