// The PCL-free shell of the baselines: input validation, normals, mesh clean-up, stage records.
#include "algorithms/baselines/baseline.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <new>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"

namespace dtsl::baselines {

std::string format_number(double value) {
  std::ostringstream s;
  s.precision(6);
  s << value;
  return s.str();
}

void rethrow_library_failure(const std::string& method, const std::string& library, const std::string& memory_hint) {
  try {
    throw;
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw AlgorithmError(method + ": out of memory inside " + library + " (" + memory_hint + ")");
  } catch (const std::exception& e) {
    throw AlgorithmError(method + ": " + library + " failed: " + e.what());
  } catch (...) {
    throw AlgorithmError(method + ": " + library + " failed with an unknown exception");
  }
}

void rethrow_pcl_failure(const std::string& method) {
  rethrow_library_failure(method, "PCL", "reduce the grid resolution, depth or input size");
}

// ---- input validation ---------------------------------------------------------------------------

Vec3 principal_extents(const std::vector<Vec3>& points) {
  if (points.empty()) return Vec3::Zero();
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& p : points) {
    const Vec3 d = p - mean;
    cov += d * d.transpose();
  }
  cov /= static_cast<double>(points.size());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov, Eigen::EigenvaluesOnly);
  const Vec3 ev = eig.eigenvalues();  // ascending
  return Vec3(std::sqrt(std::max(ev[2], 0.0)), std::sqrt(std::max(ev[1], 0.0)),
              std::sqrt(std::max(ev[0], 0.0)));
}

namespace {

struct FloatKey {
  float x, y, z;
  bool operator==(const FloatKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct FloatKeyHash {
  std::size_t operator()(const FloatKey& k) const {
    auto bits = [](float f) {
      std::uint32_t u;
      std::memcpy(&u, &f, sizeof u);
      return static_cast<std::size_t>(u);
    };
    std::size_t h = bits(k.x);
    h = h * 0x9E3779B97F4A7C15ULL ^ bits(k.y);
    h = h * 0x9E3779B97F4A7C15ULL ^ bits(k.z);
    return h ^ (h >> 29);
  }
};
// +0.0f makes -0 and +0 the same key.
FloatKey key_of(const Vec3& p) {
  return {static_cast<float>(p.x()) + 0.0f, static_cast<float>(p.y()) + 0.0f, static_cast<float>(p.z()) + 0.0f};
}

}  // namespace

std::size_t remove_duplicates(PointCloud& cloud) {
  const bool normals = cloud.has_normals();
  std::unordered_set<FloatKey, FloatKeyHash> seen;
  seen.reserve(cloud.points.size() * 2);
  std::size_t out = 0;
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    if (!seen.insert(key_of(cloud.points[i])).second) continue;
    cloud.points[out] = cloud.points[i];
    if (normals) cloud.normals[out] = cloud.normals[i];
    ++out;
  }
  const std::size_t removed = cloud.points.size() - out;
  cloud.points.resize(out);
  if (normals) cloud.normals.resize(out);
  return removed;
}

PointCloud validated_input(const std::string& method, const PointCloud& cloud, const InputRequirements& req,
                           std::size_t* duplicates_removed) {
  const std::size_t n = cloud.size();
  if (n < req.min_points)
    throw AlgorithmError(method + ": needs at least " + std::to_string(req.min_points) + " points, got " +
                         std::to_string(n));
  if (!cloud.normals.empty() && cloud.normals.size() != n)
    throw AlgorithmError(method + ": the cloud has " + std::to_string(cloud.normals.size()) +
                         " normals for " + std::to_string(n) + " points");
  check_finite(cloud, method + " input");

  PointCloud out = cloud;
  const std::size_t removed = remove_duplicates(out);
  if (duplicates_removed) *duplicates_removed = removed;
  if (out.size() < req.min_points)
    throw AlgorithmError(method + ": needs at least " + std::to_string(req.min_points) +
                         " distinct points, got " + std::to_string(out.size()) + " (of " + std::to_string(n) +
                         " points; the others coincide in single precision)");

  // Degenerate shapes: PCL's volumetric methods return garbage or nothing on them (marching cubes on
  // an axis-aligned plane divides by a zero voxel size), so refuse them with a reason instead.
  const Vec3 s = principal_extents(out.points);
  const double rel = 1e-5;  // far above float rounding (1e-7), far below any real thickness
  if (!(s[1] > rel * s[0]))
    throw AlgorithmError(method + ": the " + std::to_string(out.size()) +
                         " points are collinear (principal extents " + format_number(s[0]) + ", " +
                         format_number(s[1]) + ", " + format_number(s[2]) + "): no surface to reconstruct");
  if (req.needs_volume && !(s[2] > rel * s[0]))
    throw AlgorithmError(method + ": the " + std::to_string(out.size()) +
                         " points are coplanar (principal extents " + format_number(s[0]) + ", " +
                         format_number(s[1]) + ", " + format_number(s[2]) +
                         "): this method builds an inside/outside function and needs a 3-D point set");
  return out;
}

// ---- mesh clean-up ------------------------------------------------------------------------------

nlohmann::json CleanupCounts::to_json() const {
  return {{"polygons", polygons},
          {"triangles_before_cleanup", triangles},
          {"vertices_before_cleanup", vertices_in},
          {"vertices_welded", welded},
          {"invalid_triangles_dropped", invalid_dropped},
          {"degenerate_triangles_dropped", degenerate_dropped},
          {"duplicate_triangles_dropped", duplicate_dropped},
          {"unreferenced_vertices_removed", unreferenced_removed}};
}

namespace {

struct CellKey {
  std::int64_t x, y, z;
  bool operator==(const CellKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct CellKeyHash {
  std::size_t operator()(const CellKey& k) const {
    std::size_t h = static_cast<std::size_t>(k.x) * 73856093ULL;
    h ^= static_cast<std::size_t>(k.y) * 19349663ULL;
    h ^= static_cast<std::size_t>(k.z) * 83492791ULL;
    return h;
  }
};

// Representative index of every vertex: the first earlier finite vertex within `tol`, else itself.
std::vector<int> weld(const std::vector<Vec3>& v, double tol, std::size_t& welded) {
  std::vector<int> rep(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) rep[i] = static_cast<int>(i);
  welded = 0;
  if (!(tol > 0.0)) return rep;
  std::unordered_map<CellKey, std::vector<int>, CellKeyHash> grid;
  grid.reserve(v.size());
  const double tol2 = tol * tol;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!v[i].allFinite()) continue;
    const CellKey c{static_cast<std::int64_t>(std::floor(v[i].x() / tol)),
                    static_cast<std::int64_t>(std::floor(v[i].y() / tol)),
                    static_cast<std::int64_t>(std::floor(v[i].z() / tol))};
    int found = -1;
    for (int dx = -1; dx <= 1 && found < 0; ++dx)
      for (int dy = -1; dy <= 1 && found < 0; ++dy)
        for (int dz = -1; dz <= 1 && found < 0; ++dz) {
          auto it = grid.find({c.x + dx, c.y + dy, c.z + dz});
          if (it == grid.end()) continue;
          for (int j : it->second)
            if ((v[j] - v[i]).squaredNorm() <= tol2) {
              found = j;
              break;
            }
        }
    if (found >= 0) {
      rep[i] = found;
      ++welded;
    } else {
      grid[c].push_back(static_cast<int>(i));
    }
  }
  return rep;
}

struct TriKey {
  int a, b, c;  // sorted
  bool operator==(const TriKey& o) const { return a == o.a && b == o.b && c == o.c; }
};
struct TriKeyHash {
  std::size_t operator()(const TriKey& k) const {
    std::size_t h = static_cast<std::size_t>(k.a);
    h = h * 0x9E3779B97F4A7C15ULL ^ static_cast<std::size_t>(k.b);
    h = h * 0x9E3779B97F4A7C15ULL ^ static_cast<std::size_t>(k.c);
    return h ^ (h >> 31);
  }
};

}  // namespace

TriangleMesh soup_to_mesh(const PolygonSoup& soup, double weld_tolerance, bool flip, CleanupCounts* counts) {
  CleanupCounts c;
  c.polygons = soup.polygons.size();
  c.vertices_in = soup.vertices.size();
  const std::vector<int> rep = weld(soup.vertices, weld_tolerance, c.welded);
  const int nv = static_cast<int>(soup.vertices.size());

  std::vector<Face> faces;
  faces.reserve(soup.polygons.size());
  std::unordered_set<TriKey, TriKeyHash> seen;
  seen.reserve(soup.polygons.size() * 2);
  for (const std::vector<int>& poly : soup.polygons) {
    for (std::size_t k = 1; k + 1 < poly.size(); ++k) {
      ++c.triangles;
      Face f{poly[0], poly[k], poly[k + 1]};
      bool valid = true;
      for (int& i : f) {
        if (i < 0 || i >= nv || !soup.vertices[i].allFinite()) {
          valid = false;
          break;
        }
        i = rep[i];
      }
      if (!valid) {
        ++c.invalid_dropped;
        continue;
      }
      if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) {
        ++c.degenerate_dropped;
        continue;
      }
      std::array<int, 3> s = f;
      std::sort(s.begin(), s.end());
      if (!seen.insert({s[0], s[1], s[2]}).second) {
        ++c.duplicate_dropped;
        continue;
      }
      if (flip) std::swap(f[1], f[2]);
      faces.push_back(f);
    }
  }

  // Keep referenced vertices only, in their original order.
  std::vector<int> new_index(soup.vertices.size(), -1);
  for (const Face& f : faces)
    for (int i : f) new_index[i] = 0;
  TriangleMesh mesh;
  for (std::size_t i = 0; i < soup.vertices.size(); ++i) {
    if (new_index[i] < 0) continue;
    new_index[i] = static_cast<int>(mesh.vertices.size());
    mesh.vertices.push_back(soup.vertices[i]);
  }
  // Welded-away vertices are never referenced, so they count among the removed ones only if they
  // were not welded: report them separately.
  c.unreferenced_removed = soup.vertices.size() - mesh.vertices.size() - c.welded;
  for (Face& f : faces)
    for (int& i : f) i = new_index[i];
  mesh.faces = std::move(faces);
  if (counts) *counts = c;
  return mesh;
}

// ---- the common body ----------------------------------------------------------------------------

ReconstructionResult PclBaseline::reconstruct(const PointCloud& points, const RunContext& context) {
  options().check();
  std::size_t duplicates = 0;
  PointCloud cloud = validated_input(name_, points, requirements(), &duplicates);
  check_input(cloud);

  ReconstructionResult result;

  // Stage 1: normals from the configured source.
  StageRecord normals_stage;
  normals_stage.name = "normals";
  Stopwatch normals_clock;
  std::string source;
  PointCloud oriented;
  try {
    oriented = with_normals(cloud, normal_options(), source);
  } catch (const AlgorithmError& e) {
    throw AlgorithmError(name_ + ": " + e.what());  // e.g. "normals: source 'ground_truth' requested but ..."
  }
  normals_stage.seconds = normals_clock.seconds();
  if (oriented.normals.size() != oriented.points.size() || oriented.points.size() != cloud.points.size())
    throw AlgorithmError(name_ + ": the normal source '" + source + "' returned " +
                         std::to_string(oriented.normals.size()) + " normals for " +
                         std::to_string(cloud.points.size()) + " points");
  for (std::size_t i = 0; i < oriented.normals.size(); ++i) {
    Vec3& n = oriented.normals[i];
    const double len = n.norm();
    if (!std::isfinite(len) || len < 1e-12)
      throw AlgorithmError(name_ + ": normal " + std::to_string(i) + " from source '" + source +
                           "' is zero or not finite");
    n /= len;
  }
  normals_stage.summary = {{"source", source}, {"points", oriented.size()}};
  result.stages.push_back(std::move(normals_stage));

  // Stage 2: the PCL method.
  TriangleMesh mesh;
  result.stages.push_back(reconstruct_stage(
      name_, oriented.size(), [&](nlohmann::json& summary) { return run(oriented, context, summary); },
      [this] { return empty_hint(); }, mesh));

  result.summary["normals_source"] = source;
  result.summary["input_points"] = points.size();
  result.summary["duplicates_removed"] = duplicates;
  result.mesh = std::move(mesh);
  return result;
}

StageRecord reconstruct_stage(const std::string& method, std::size_t points,
                              const std::function<TriangleMesh(nlohmann::json&)>& run,
                              const std::function<std::string()>& hint, TriangleMesh& mesh) {
  StageRecord stage;
  stage.name = "reconstruct";
  Stopwatch clock;
  nlohmann::json summary = nlohmann::json::object();
  summary["input_points"] = points;
  mesh = run(summary);
  stage.seconds = clock.seconds();
  if (mesh.faces.empty())
    throw AlgorithmError(method + " produced no triangles from " + std::to_string(points) + " points; " + hint());
  summary["vertices"] = mesh.vertices.size();
  summary["faces"] = mesh.faces.size();
  stage.summary = std::move(summary);
  return stage;
}

ReconstructionResult PointsBaseline::reconstruct(const PointCloud& points, const RunContext& context) {
  options().check();
  std::size_t duplicates = 0;
  const PointCloud cloud = validated_input(name_, points, requirements(), &duplicates);
  ReconstructionResult result;
  TriangleMesh mesh;
  result.stages.push_back(reconstruct_stage(
      name_, cloud.size(), [&](nlohmann::json& summary) { return run(cloud, context, summary); },
      [this] { return empty_hint(); }, mesh));
  result.summary["normals_source"] = normals_source();
  result.summary["input_points"] = points.size();
  result.summary["duplicates_removed"] = duplicates;
  result.mesh = std::move(mesh);
  return result;
}

bool orient_outward(TriangleMesh& mesh, const Vec3& centre) {
  double volume = 0.0;
  for (const Face& f : mesh.faces) {
    const Vec3 a = mesh.vertices[f[0]] - centre, b = mesh.vertices[f[1]] - centre, c = mesh.vertices[f[2]] - centre;
    volume += a.dot(b.cross(c));
  }
  if (!(volume < 0.0)) return false;
  for (Face& f : mesh.faces) std::swap(f[1], f[2]);
  return true;
}

}  // namespace dtsl::baselines
