// Lean geometric core types: a point cloud with optional normals and an indexed triangle mesh.
// Plain structs of Eigen vectors so every algorithm can read them without adapters.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products, used throughout
#include <array>
#include <limits>
#include <string>
#include <vector>

namespace dtsl {

using Vec3 = Eigen::Vector3d;
using Face = std::array<int, 3>;

/// Unorganised points; `normals` is either empty or has one unit normal per point.
struct PointCloud {
  std::vector<Vec3> points;
  std::vector<Vec3> normals;

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  bool has_normals() const { return !points.empty() && normals.size() == points.size(); }
};

/// Indexed triangle mesh; `normals` is either empty or has one unit normal per vertex.
struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<Face> faces;
  std::vector<Vec3> normals;

  bool has_normals() const { return !vertices.empty() && normals.size() == vertices.size(); }
};

/// Axis-aligned bounding box.
struct BoundingBox {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());

  void extend(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  bool valid() const { return (min.array() <= max.array()).all(); }
  Vec3 center() const { return 0.5 * (min + max); }
  Vec3 extent() const { return max - min; }
  double diagonal() const { return extent().norm(); }
};

BoundingBox bounding_box(const std::vector<Vec3>& points);

/// x -> scale * (x - center): the map into the paper's [-1,1]^3 frame (bbox centre to the origin,
/// longest side to 2).
struct Similarity {
  Vec3 center = Vec3::Zero();
  double scale = 1.0;

  Vec3 apply(const Vec3& x) const { return scale * (x - center); }
  Vec3 invert(const Vec3& y) const { return y / scale + center; }
  /// The map back: inverse().apply(apply(x)) == x.
  Similarity inverse() const { return {-center * scale, 1.0 / scale}; }
  /// This map followed by `next`: then(next).apply(x) == next.apply(apply(x)).
  Similarity then(const Similarity& next) const { return {center + next.center / scale, scale * next.scale}; }
};

/// The similarity that maps the box of `points` into [-1,1]^3. Throws AlgorithmError (naming `what`)
/// for an empty set or a set whose points all coincide.
Similarity unit_cube_normalisation(const std::vector<Vec3>& points, const std::string& what);

void transform(PointCloud& cloud, const Similarity& s);
void transform(TriangleMesh& mesh, const Similarity& s);

/// Throws AlgorithmError naming `what` and the first offending index if a coordinate is NaN or
/// infinite, or a normal is not finite.
void check_finite(const PointCloud& cloud, const std::string& what);
void check_finite(const TriangleMesh& mesh, const std::string& what);

}  // namespace dtsl
