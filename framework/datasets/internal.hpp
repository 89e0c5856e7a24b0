// Private to the datasets module: the registration functions of each plugin file and the small mesh
// helpers the shape sources and samplers share. Not installed, not included outside framework/datasets.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "framework/core/types.hpp"

namespace dtsl::dataset_detail {

// One per plugin file; register_dataset_plugins() calls each once.
void register_synthetic_shapes();  // sphere, torus, two_spheres (synthetic_shapes.cpp)
void register_block_shape();       // block (block.cpp)
void register_plate_shapes();      // plate_holes, high_genus (plate_shapes.cpp)
void register_lattice_shape();     // lattice (lattice.cpp)
void register_pair_shape();        // pair (pair.cpp)
void register_dumbbell_shape();    // dumbbell (dumbbell.cpp)
void register_model_shapes();      // cgal_model, file (model_shapes.cpp)
void register_samplers();          // vertices, area, none (samplers.cpp)
void register_corruptions();       // noise, holes, plane_cut, outliers, subsample (corruptions.cpp)

/// Unit vertex normals as the area-weighted mean of the incident faces' normals (the cross products
/// are summed unnormalised, which weights by area). A vertex with no incident face of positive area
/// gets a zero vector: callers decide what that means.
std::vector<Vec3> area_weighted_vertex_normals(const TriangleMesh& mesh);

/// Unit vertex normals weighted by the incident corner angles: on a tessellated flat face they are
/// exactly that face's normal however the triangles are cut, which area weighting does not give.
std::vector<Vec3> angle_weighted_vertex_normals(const TriangleMesh& mesh);

/// Volume enclosed by the mesh (divergence theorem); positive when its faces are oriented outward.
/// For an open mesh it is the volume of the cone fan to the origin: still a usable orientation sign.
double signed_volume(const TriangleMesh& mesh);

/// Flips every face (and negates vertex normals) if the signed volume is negative, so that face and
/// vertex normals point outward. Returns whether it flipped.
bool orient_outward(TriangleMesh& mesh);

/// Whether each vertex is a corner of at least one face.
std::vector<bool> referenced_vertices(const TriangleMesh& mesh);

/// An icosphere: the icosahedron split `subdivisions` times, vertices on the sphere, outward faces and
/// analytic vertex normals. 10 * 4^s + 2 vertices.
TriangleMesh icosphere(const Vec3& centre, double radius, int subdivisions);

/// A smooth closed surface {f = 0}, f < 0 inside, with the topology it is built to have.
struct ImplicitSurface {
  std::function<double(const Vec3&)> f;
  BoundingBox box;     ///< holds the whole surface, with f > 0 on its boundary
  int components = 1;  ///< connected components of the surface
  int genus = 0;       ///< total genus (sum over the components)
};

/// A closed, outward-oriented triangle mesh of `s` with edges of about `edge_length` (finer where the
/// surface curves), vertices on the surface and f's normalised gradient as their normals
/// (implicit_mesher.cpp). Features must be about 4 edge lengths thick (the shapes' option checks see to
/// it). Deterministic. Throws AlgorithmError naming `what` if the mesh does not have the surface's
/// components and genus (`edge_length` too coarse for its thinnest feature).
TriangleMesh mesh_implicit_surface(const ImplicitSurface& s, double edge_length, const std::string& what);

/// Appends `part` to `mesh` (vertices, faces re-indexed, normals).
void append(TriangleMesh& mesh, const TriangleMesh& part);

/// A vector option of length 3 as a Vec3 (the option's check() has verified the length).
Vec3 to_vec3(const std::vector<double>& v);

/// A number for a message: shortest form that reads back the same ("0.4", not "0.400000").
std::string format_number(double v);

}  // namespace dtsl::dataset_detail
