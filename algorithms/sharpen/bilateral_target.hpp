// The bilateral target of a vertex (paper Eq. 8, after ref [53]):
//   v' = sum_{T_j in N(v)} W_c(|v - c_j|) W_s(|v - v*_j|) alpha_j v*_j / W,
// v*_j the projection of v onto the plane of triangle T_j, c_j its centroid, alpha_j its area, W the
// sum of the weights, W_c, W_s Gaussians exp(-x^2 / 2 sigma^2). Projections onto the planes of the
// faces on both sides of a rounded edge pull v towards the planes' intersection: the sharp edge.
#pragma once

#include "framework/core/mesh_adjacency.hpp"
#include "framework/core/types.hpp"

namespace dtsl::sharpen {

/// N(v): the triangles whose centroid lies within `radius` of v, found by walking the mesh from v's
/// one-ring (faces reached through vertices within the radius). With sigma_c as Gaussian width, a
/// radius of 2 sigma_c keeps every triangle of weight above e^-2.
Vec3 bilateral_target(const TriangleMesh& mesh, const MeshAdjacency& adj, int v, double sigma_c, double sigma_s,
                      double radius);

}  // namespace dtsl::sharpen
