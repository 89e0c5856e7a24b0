// Readers and writers of point clouds and triangle meshes. The format is chosen by the file extension
// (case-insensitive): .ply (ascii and binary little/big endian), .obj, .off, .xyz (x y z [nx ny nz] per
// line), .pcd (through PCL, points only). Every error is a FileError naming the file and the line (text)
// or element (binary). Writers are atomic (write to a temporary, then rename).
#pragma once

#include <string>

#include "framework/core/types.hpp"

namespace dtsl {

/// Points of any supported file: a mesh file's vertices (with its vertex normals if it has them).
/// Rejects empty files and NaN/infinite coordinates.
PointCloud read_points(const std::string& path);

/// A triangle mesh (.ply, .obj, .off); polygons with more than 3 corners are fan-triangulated. Rejects
/// out-of-range or negative indices (OBJ's relative negative indices are resolved), NaN coordinates.
TriangleMesh read_mesh(const std::string& path);

struct WriteOptions {
  bool binary = true;  ///< PLY and PCD: binary little-endian; ignored by text-only formats
};

/// Writers keep normals when there is one per point/vertex. PLY stores doubles and text formats the
/// shortest decimal that reads back exactly, so a round trip is lossless; OFF with normals is written
/// as NOFF, OBJ as v/vn with "f a//a ..."; PCD stores float32 (PCL's convention). Refuses (FileError,
/// nothing written) NaN/infinite coordinates, face indices out of range, and meshes to .xyz/.pcd.
void write_points(const std::string& path, const PointCloud& cloud, const WriteOptions& options = {});
void write_mesh(const std::string& path, const TriangleMesh& mesh, const WriteOptions& options = {});

/// Lower-case extension without the dot ("ply"); empty if none.
std::string file_extension(const std::string& path);

}  // namespace dtsl
