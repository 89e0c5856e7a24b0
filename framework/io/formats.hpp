// Private to framework/io: one reader and one writer per format, dispatched by io.cpp on the extension.
// Every reader returns what the file holds as an indexed mesh (vertices, per-vertex normals if the file
// has them for every vertex, fan-triangulated faces; no faces for point formats), checked: finite
// coordinates, indices in range. Emptiness (no points / no faces) is judged by the caller, which knows
// what was asked for. Writers receive data io.cpp has already checked.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "framework/core/types.hpp"

namespace dtsl::io_detail {

// Readers parse the whole content `text` of the file `path` (which only names it in messages); io.cpp
// loads it with load_file(). Taking the bytes rather than the path lets the fuzz targets (fuzz/) feed
// them straight from memory.
TriangleMesh read_ply(const std::string& path, std::string_view text);
TriangleMesh read_obj(const std::string& path, std::string_view text);
TriangleMesh read_off(const std::string& path, std::string_view text);
TriangleMesh read_xyz(const std::string& path, std::string_view text);

// `normals` is empty or one per vertex; `faces` is empty for a point cloud.
void write_ply(const std::string& path, const std::vector<Vec3>& vertices, const std::vector<Vec3>& normals,
               const std::vector<Face>& faces, bool binary);
void write_obj(const std::string& path, const std::vector<Vec3>& vertices, const std::vector<Vec3>& normals,
               const std::vector<Face>& faces);
void write_off(const std::string& path, const std::vector<Vec3>& vertices, const std::vector<Vec3>& normals,
               const std::vector<Face>& faces);
void write_xyz(const std::string& path, const std::vector<Vec3>& points, const std::vector<Vec3>& normals);

}  // namespace dtsl::io_detail
