// The public entry points: choose the format by extension, judge what the caller asked for (points,
// faces), and check data before a writer turns it into a file that could not be read back.
#include "framework/io/io.hpp"

#include <cctype>
#include <string>

#include "framework/core/error.hpp"
#include "framework/io/file_buffer.hpp"
#include "framework/io/formats.hpp"
#include "framework/io/pcd_io.hpp"

namespace dtsl {
namespace {

enum class Format { ply, obj, off, xyz, pcd };

const char* const kSupported = "supported: .ply, .obj, .off, .xyz, .pcd";

Format format_of(const std::string& path) {
  const std::string ext = file_extension(path);
  if (ext == "ply") return Format::ply;
  if (ext == "obj") return Format::obj;
  if (ext == "off") return Format::off;
  if (ext == "xyz") return Format::xyz;
  if (ext == "pcd") return Format::pcd;
  if (ext.empty()) throw FileError(path, std::string("no file extension to tell the format (") + kSupported + ")");
  throw FileError(path, "unknown file extension '." + ext + "' (" + kSupported + ")");
}

TriangleMesh read_any(const std::string& path, Format format) {
  switch (format) {
    case Format::ply: return io_detail::read_ply(path, io_detail::load_file(path));
    case Format::obj: return io_detail::read_obj(path, io_detail::load_file(path));
    case Format::off: return io_detail::read_off(path, io_detail::load_file(path));
    case Format::xyz: return io_detail::read_xyz(path, io_detail::load_file(path));
    case Format::pcd: {
      PointCloud c = io_detail::read_pcd(path);
      TriangleMesh m;
      m.vertices = std::move(c.points);
      m.normals = std::move(c.normals);
      return m;
    }
  }
  return {};
}

// Writers get normals only when there is one per vertex; a file that reads back with NaN or dangling
// indices would fail later, far from its cause, so such data is refused here.
void check_writable(const std::string& path, const std::vector<Vec3>& vertices, const std::vector<Vec3>& normals,
                    const std::vector<Face>& faces) {
  for (std::size_t i = 0; i < vertices.size(); ++i)
    if (!vertices[i].allFinite())
      throw FileError(path, "cannot write vertex " + std::to_string(i) + ": NaN or infinite coordinate");
  for (std::size_t i = 0; i < normals.size(); ++i)
    if (!normals[i].allFinite())
      throw FileError(path, "cannot write normal " + std::to_string(i) + ": NaN or infinite coordinate");
  const long long n = static_cast<long long>(vertices.size());
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int c = 0; c < 3; ++c)
      if (faces[f][c] < 0 || faces[f][c] >= n)
        throw FileError(path, "cannot write face " + std::to_string(f) + ": vertex index " +
                                  std::to_string(faces[f][c]) + " out of range (" + std::to_string(n) + " vertices)");
}

const char* format_name(Format f) {
  switch (f) {
    case Format::ply: return "PLY";
    case Format::obj: return "OBJ";
    case Format::off: return "OFF";
    case Format::xyz: return "XYZ";
    case Format::pcd: return "PCD";
  }
  return "?";
}

}  // namespace

std::string file_extension(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t start = slash == std::string::npos ? 0 : slash + 1;
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || dot <= start) return "";  // no dot in the name, or a hidden file
  std::string ext = path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

PointCloud read_points(const std::string& path) {
  TriangleMesh m = read_any(path, format_of(path));
  if (m.vertices.empty()) throw FileError(path, "contains no points");
  PointCloud cloud;
  cloud.points = std::move(m.vertices);
  if (m.normals.size() == cloud.points.size()) cloud.normals = std::move(m.normals);
  return cloud;
}

TriangleMesh read_mesh(const std::string& path) {
  const Format format = format_of(path);
  if (format == Format::xyz || format == Format::pcd)
    throw FileError(path, std::string(format_name(format)) +
                              " files hold points only, not a mesh (meshes: .ply, .obj, .off)");
  TriangleMesh m = read_any(path, format);
  if (m.faces.empty()) throw FileError(path, "contains no faces (a mesh was expected)");
  if (m.normals.size() != m.vertices.size()) m.normals.clear();
  return m;
}

void write_points(const std::string& path, const PointCloud& cloud, const WriteOptions& options) {
  const Format format = format_of(path);
  static const std::vector<Vec3> none;
  const std::vector<Vec3>& normals = cloud.has_normals() ? cloud.normals : none;
  check_writable(path, cloud.points, normals, {});
  switch (format) {
    case Format::ply: io_detail::write_ply(path, cloud.points, normals, {}, options.binary); break;
    case Format::obj: io_detail::write_obj(path, cloud.points, normals, {}); break;
    case Format::off: io_detail::write_off(path, cloud.points, normals, {}); break;
    case Format::xyz: io_detail::write_xyz(path, cloud.points, normals); break;
    case Format::pcd: {
      PointCloud c;
      c.points = cloud.points;
      c.normals = normals;
      io_detail::write_pcd(path, c, options.binary);
      break;
    }
  }
}

void write_mesh(const std::string& path, const TriangleMesh& mesh, const WriteOptions& options) {
  const Format format = format_of(path);
  if (format == Format::xyz || format == Format::pcd)
    throw FileError(path, std::string("cannot write a mesh as ") + format_name(format) +
                              ": the format holds points only (meshes: .ply, .obj, .off)");
  static const std::vector<Vec3> none;
  const std::vector<Vec3>& normals = mesh.has_normals() ? mesh.normals : none;
  check_writable(path, mesh.vertices, normals, mesh.faces);
  switch (format) {
    case Format::ply: io_detail::write_ply(path, mesh.vertices, normals, mesh.faces, options.binary); break;
    case Format::obj: io_detail::write_obj(path, mesh.vertices, normals, mesh.faces); break;
    case Format::off: io_detail::write_off(path, mesh.vertices, normals, mesh.faces); break;
    default: break;
  }
}

}  // namespace dtsl
