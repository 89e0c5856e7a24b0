#include "algorithms/sharpen/sharp_vertices.hpp"

#include <algorithm>
#include <cmath>

#include "framework/core/sampling.hpp"

namespace dtsl::sharpen {

void SharpVertexOptions::visit(FieldVisitor& v) {
  v.field("dihedral_angle_deg", dihedral_angle_deg,
          "one-ring dihedral angle (deg) above which a vertex is a potential sharp vertex (ref [53])");
  v.field("normal_variation_deg", normal_variation_deg,
          "angle (deg) between the vertex normal and a nearby triangle's normal above which a vertex is also "
          "potentially sharp (rounded edges of a displaced mesh); 0 turns it off");
  v.field("normal_variation_rings", normal_variation_rings, "edge hops of the normal-variation neighbourhood");
  v.field("error_ratio", error_ratio,
          "keep a potential sharp vertex only if its one-ring's data are farther than error_ratio x e_avr");
  v.field("min_points", min_points, "data foot points the one-ring must hold to be judged at all");
}

void SharpVertexOptions::check() const {
  check_range("dihedral_angle_deg", dihedral_angle_deg, 0.0, 180.0);
  check_range("normal_variation_deg", normal_variation_deg, 0.0, 180.0);
  check_range("normal_variation_rings", normal_variation_rings, 1, 10);
  check_non_negative("error_ratio", error_ratio);
  check_range("min_points", min_points, 0, 1000000);
}

std::vector<Vec3> vertex_normals(const TriangleMesh& mesh, const MeshAdjacency& adj) {
  std::vector<Vec3> n(mesh.vertices.size(), Vec3::Zero());
  for (std::size_t v = 0; v < n.size(); ++v) {
    for (const int f : adj.vertex_faces[v]) {
      const Face& t = mesh.faces[f];
      n[v] += (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
    }
    const double len = n[v].norm();
    if (len > 0.0) n[v] /= len;
  }
  return n;
}

SharpVertices detect_sharp_vertices(const TriangleMesh& mesh, const MeshAdjacency& adj,
                                    const std::vector<FootPoint>& feet, const SharpVertexOptions& o) {
  const int nv = static_cast<int>(mesh.vertices.size());
  const int nf = static_cast<int>(mesh.faces.size());
  std::vector<Vec3> fn(nf);
  for (int f = 0; f < nf; ++f) fn[f] = face_normal(mesh, f);
  const std::vector<Vec3> vn = vertex_normals(mesh, adj);

  // Per-face data statistics, for the one-ring fitting error.
  std::vector<double> face_err(nf, 0.0);
  std::vector<int> face_cnt(nf, 0);
  double e_avr = 0.0;
  for (const auto& f : feet) {
    face_err[f.face] += f.distance;
    ++face_cnt[f.face];
    e_avr += f.distance;
  }
  if (!feet.empty()) e_avr /= static_cast<double>(feet.size());

  const double cos_dihedral = std::cos(o.dihedral_angle_deg * M_PI / 180.0);
  const double cos_variation = std::cos(o.normal_variation_deg * M_PI / 180.0);
  SharpVertices out;
  for (int v = 0; v < nv; ++v) {
    const auto& ring = adj.vertex_faces[v];
    if (ring.empty()) continue;
    // Dihedral angles of every edge between two one-ring faces (the spokes and, through shared
    // vertices, the ring's own adjacency).
    bool dihedral = false;
    for (std::size_t a = 0; a < ring.size() && !dihedral; ++a)
      for (std::size_t b = a + 1; b < ring.size() && !dihedral; ++b) {
        const Face& fa = mesh.faces[ring[a]];
        const Face& fb = mesh.faces[ring[b]];
        int shared = 0;
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) shared += fa[i] == fb[j];
        if (shared == 2 && fn[ring[a]].dot(fn[ring[b]]) < cos_dihedral) dihedral = true;
      }
    bool variation = false;
    if (!dihedral && o.normal_variation_deg > 0.0) {
      for (const int w : k_ring(adj, v, o.normal_variation_rings - 1)) {
        for (const int f : adj.vertex_faces[w])
          if (fn[f].dot(vn[v]) < cos_variation) {
            variation = true;
            break;
          }
        if (variation) break;
      }
    }
    if (!dihedral && !variation) continue;
    ++out.potential;
    out.by_dihedral += dihedral;
    double err = 0.0;
    int cnt = 0;
    for (const int f : ring) {
      err += face_err[f];
      cnt += face_cnt[f];
    }
    if (cnt == 0 || cnt < o.min_points) continue;
    if (err / cnt > o.error_ratio * e_avr) out.vertices.push_back(v);
  }
  return out;
}

}  // namespace dtsl::sharpen
