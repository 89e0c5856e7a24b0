// Samplers: how a shape becomes points. Every point carries the ground truth's normal there, so a
// method that needs oriented normals can be given true ones (and the results say so).
#include <algorithm>
#include <cmath>
#include <functional>

#include "framework/core/error.hpp"
#include "framework/core/sampling.hpp"
#include "framework/datasets/dataset.hpp"
#include "framework/datasets/internal.hpp"

namespace dtsl::dataset_detail {

namespace {

const TriangleMesh& require_mesh(const ShapeData& shape, const char* sampler) {
  if (!shape.mesh || shape.mesh->faces.empty())
    throw AlgorithmError(std::string("sampler '") + sampler +
                         "' needs a surface mesh, but the shape has none (use sampler 'none' for a "
                         "shape that supplies its own points)");
  return *shape.mesh;
}

// ---- vertices ---------------------------------------------------------------------------------

/// The paper's inputs are the vertices of scans, so this is the sampler closest to its data.
class Vertices final : public Sampler {
 public:
  Options& options() override { return o_; }
  PointCloud sample(const ShapeData& shape, std::mt19937_64&) override {
    const TriangleMesh& mesh = require_mesh(shape, "vertices");
    const std::vector<Vec3> computed = area_weighted_vertex_normals(mesh);
    const std::vector<bool> used = referenced_vertices(mesh);
    PointCloud cloud;
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
      // A vertex no face uses is not on the surface (stray vertices are common in model files).
      if (!used[i]) continue;
      Vec3 n = mesh.has_normals() ? mesh.normals[i] : computed[i];
      if (!(n.allFinite() && n.norm() > 0.5)) n = computed[i];  // a file's missing or broken normal
      // Only degenerate triangles around it: no surface direction, so no sample either.
      if (n.isZero()) continue;
      cloud.points.push_back(mesh.vertices[i]);
      // Renormalise only what is not unit already: exact normals stay bit for bit the ground truth's.
      cloud.normals.push_back(std::abs(n.norm() - 1.0) < 1e-12 ? n : Vec3(n.normalized()));
    }
    return cloud;
  }

 private:
  NoOptions o_;
};

// ---- area -------------------------------------------------------------------------------------

struct AreaOptions final : Options {
  int count = 20000;
  double density_ratio = 1.0;
  std::string density_axis = "x";

  void visit(FieldVisitor& v) override {
    v.field("count", count, "number of points");
    v.field("density_ratio", density_ratio,
            "max / min point density (points per area) over the shape; 1 = area-uniform. The density "
            "grows exponentially along density_axis, from the shape's low end to its high end");
    v.field("density_axis", density_axis,
            "direction the density grows in: x, y, z (across the shape's box), or radial (from the box "
            "centre to the farthest vertex)");
  }
  void check() const override {
    check_range("count", count, 1, 100000000);
    // Past 1e6 the sparse end has no point at any usable count.
    check_range("density_ratio", density_ratio, 1.0, 1e6);
    check_one_of("density_axis", density_axis, {"x", "y", "z", "radial"});
  }
};

class Area final : public Sampler {
 public:
  Options& options() override { return o_; }
  PointCloud sample(const ShapeData& shape, std::mt19937_64& rng) override {
    const TriangleMesh& mesh = require_mesh(shape, "area");
    std::vector<SurfaceSample> samples;
    if (o_.density_ratio == 1.0) {
      samples = sample_surface(mesh, static_cast<std::size_t>(o_.count), rng);
    } else {
      // position(p) in [0,1] along the chosen direction; density = ratio^position, so max/min over
      // the shape is exactly the ratio and the density's log-gradient is constant.
      const BoundingBox box = bounding_box(mesh.vertices);
      const double log_ratio = std::log(o_.density_ratio);
      std::function<double(const Vec3&)> position;
      if (o_.density_axis == "radial") {
        const Vec3 c = box.center();
        double reach = 0.0;
        for (const Vec3& v : mesh.vertices) reach = std::max(reach, (v - c).norm());
        position = [c, reach](const Vec3& p) { return reach > 0.0 ? (p - c).norm() / reach : 0.0; };
      } else {
        const int axis = o_.density_axis[0] - 'x';
        const double lo = box.min[axis], extent = box.extent()[axis];
        position = [axis, lo, extent](const Vec3& p) { return extent > 0.0 ? (p[axis] - lo) / extent : 0.0; };
      }
      samples = sample_surface_weighted(mesh, static_cast<std::size_t>(o_.count), rng,
                                        [&](const Vec3& p) { return std::exp(log_ratio * position(p)); });
    }
    PointCloud cloud;
    cloud.points.reserve(samples.size());
    cloud.normals.reserve(samples.size());
    for (const SurfaceSample& s : samples) {
      cloud.points.push_back(s.point);
      // The ground truth is the mesh, so its normal at the point is the sampled face's (the metrics'
      // normal consistency uses the same).
      cloud.normals.push_back(s.normal);
    }
    return cloud;
  }

 private:
  AreaOptions o_;
};

// ---- none -------------------------------------------------------------------------------------

class None final : public Sampler {
 public:
  Options& options() override { return o_; }
  PointCloud sample(const ShapeData& shape, std::mt19937_64&) override {
    if (!shape.points)
      throw AlgorithmError("sampler 'none' needs a shape that supplies points (file with `points`)");
    return *shape.points;
  }

 private:
  NoOptions o_;
};

}  // namespace

void register_samplers() {
  samplers().add("vertices", "the mesh's vertices with its vertex normals (the paper's scan vertices)",
                 [] { return std::make_unique<Vertices>(); });
  samplers().add("area", "count points by area, uniform or with density varying along an axis / radially",
                 [] { return std::make_unique<Area>(); });
  samplers().add("none", "the shape's own points (file sources)", [] { return std::make_unique<None>(); });
}

}  // namespace dtsl::dataset_detail
