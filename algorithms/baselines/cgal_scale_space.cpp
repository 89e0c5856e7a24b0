// cgal_scale_space: CGAL's scale-space surface reconstruction (Digne et al., 2011). The points are
// smoothed a few times (a coarser scale, where noise no longer confuses the mesher), meshed there, and
// the connectivity is carried back to the original points, so the mesh interpolates the input without
// needing normals.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Scale_space_reconstruction_3/Advancing_front_mesher.h>
#include <CGAL/Scale_space_reconstruction_3/Alpha_shape_mesher.h>
#include <CGAL/Scale_space_reconstruction_3/Jet_smoother.h>
#include <CGAL/Scale_space_reconstruction_3/Weighted_PCA_smoother.h>
#include <CGAL/Scale_space_surface_reconstruction_3.h>
#include <CGAL/Search_traits_3.h>

#include <cmath>

#include "algorithms/baselines/baseline.hpp"
#include "algorithms/baselines/cgal_support.hpp"

namespace dtsl::baselines {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using ScaleSpace = CGAL::Scale_space_surface_reconstruction_3<Kernel>;

struct ScaleSpaceOptions final : Options {
  int iterations = 4;
  std::string smoother = "jet";
  int neighbors = 12;
  std::string mesher = "advancing_front";
  double max_facet_length = 0.0;
  double radius_ratio_bound = 5.0;
  double beta = 0.52;
  bool force_manifold = true;
  std::string output_points = "original";

  void visit(FieldVisitor& v) override {
    v.field("iterations", iterations,
            "smoothing iterations: how far up the scale space the points are meshed; 0 meshes the raw "
            "points (CGAL's example: 4)");
    v.field("smoother", smoother,
            "jet (CGAL's jet_smooth_point_set over `neighbors` points) or weighted_pca (projection on the "
            "weighted PCA plane of the neighbourhood ball, Digne et al.'s original operator)");
    v.field("neighbors", neighbors,
            "neighbourhood size k, scale-free: the jet fit's point count; the ball of weighted_pca and "
            "alpha_shape has the mean distance to the k-th nearest neighbour as radius (CGAL default 12)");
    v.field("mesher", mesher,
            "advancing_front (CGAL's advancing front on the smoothed points) or alpha_shape (the "
            "boundary of the alpha shape whose radius is the neighbourhood radius)");
    v.field("max_facet_length", max_facet_length,
            "advancing_front: longest edge allowed, in neighbourhood radii; 0 means no bound (CGAL default 0)");
    v.field("radius_ratio_bound", radius_ratio_bound,
            "advancing_front: as cgal_advancing_front's radius_ratio_bound (CGAL default 5)");
    v.field("beta", beta, "advancing_front: as cgal_advancing_front's beta, radians (CGAL default 0.52)");
    v.field("force_manifold", force_manifold,
            "alpha_shape: drop the facets that make the surface non-manifold and orient the rest "
            "consistently; CGAL's default false keeps inner sheets and orients facets arbitrarily");
    v.field("output_points", output_points,
            "original (the connectivity carried back to the input points, as Digne et al.) or smoothed "
            "(the mesh at the coarse scale)");
  }

  void check() const override {
    check_range("iterations", iterations, 0, 1000);
    check_one_of("smoother", smoother, {"jet", "weighted_pca"});
    check_range("neighbors", neighbors, 3, 1000);
    check_one_of("mesher", mesher, {"advancing_front", "alpha_shape"});
    check_range("max_facet_length", max_facet_length, 0.0, 1e6);
    check_range("radius_ratio_bound", radius_ratio_bound, 1.0, 1e6);
    check_range("beta", beta, 0.0, M_PI / 2);
    check_one_of("output_points", output_points, {"original", "smoothed"});
  }
};

/// Mean distance from each point to its k-th nearest other point: CGAL's neighbourhood radius
/// estimate (Weighted_PCA_smoother samples 300 points at random; all of them here, so the radius
/// does not depend on a random draw).
double neighbourhood_radius(const std::vector<Point>& points, int k) {
  using Traits = CGAL::Search_traits_3<Kernel>;
  using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;
  Search::Tree tree(points.begin(), points.end());
  tree.build();
  double sum = 0.0;
  for (const Point& p : points) {
    Search search(tree, p, static_cast<unsigned>(k) + 1);  // the point itself comes first
    double farthest = 0.0;
    for (const auto& neighbour : search) farthest = std::max(farthest, neighbour.second);
    sum += std::sqrt(farthest);  // the search reports squared distances
  }
  return sum / static_cast<double>(points.size());
}

class ScaleSpaceBaseline final : public PointsBaseline {
 public:
  ScaleSpaceBaseline() : PointsBaseline("cgal_scale_space") {}
  Options& options() override { return options_; }

 protected:
  InputRequirements requirements() const override {
    return {static_cast<std::size_t>(std::max(10, options_.neighbors + 1)), false};
  }

  TriangleMesh run(const PointCloud& cloud, const RunContext&, nlohmann::json& summary) override {
    const ScaleSpaceOptions& o = options_;
    std::vector<Point> points;
    points.reserve(cloud.size());
    for (const Vec3& p : cloud.points) points.emplace_back(p.x(), p.y(), p.z());
    double radius = 0.0;
    std::vector<std::array<std::size_t, 3>> facets;
    std::vector<Vec3> smoothed;
    guarded_cgal_call(name(), [&] {
      radius = neighbourhood_radius(points, o.neighbors);
      ScaleSpace space(points.begin(), points.end());
      if (o.smoother == "jet")
        space.increase_scale(o.iterations, CGAL::Scale_space_reconstruction_3::Jet_smoother<Kernel>(o.neighbors));
      else
        space.increase_scale(o.iterations, CGAL::Scale_space_reconstruction_3::Weighted_PCA_smoother<Kernel>(radius * radius));
      if (o.mesher == "advancing_front")
        space.reconstruct_surface(CGAL::Scale_space_reconstruction_3::Advancing_front_mesher<Kernel>(
            o.max_facet_length * radius, o.radius_ratio_bound, o.beta));
      else
        space.reconstruct_surface(CGAL::Scale_space_reconstruction_3::Alpha_shape_mesher<Kernel>(
            radius * radius, false, o.force_manifold));
      facets.assign(space.facets_begin(), space.facets_end());
      if (o.output_points == "smoothed")
        for (auto it = space.points_begin(); it != space.points_end(); ++it)
          smoothed.emplace_back(it->x(), it->y(), it->z());
    });
    summary["neighbourhood_radius"] = radius;
    if (o.output_points == "smoothed" && smoothed.size() != cloud.size())
      throw AlgorithmError(name() + ": the scale space returned " + std::to_string(smoothed.size()) +
                           " smoothed points for " + std::to_string(cloud.size()));
    return interpolating_mesh(o.output_points == "smoothed" ? smoothed : cloud.points, facets, summary);
  }

  std::string empty_hint() const override {
    return options_.mesher == "alpha_shape"
               ? "raise neighbors (now " + std::to_string(options_.neighbors) + ") for a larger alpha shape radius"
               : "the points may be too sparse: raise radius_ratio_bound (now " +
                     format_number(options_.radius_ratio_bound) + ")";
  }

 private:
  ScaleSpaceOptions options_;
};

}  // namespace

std::unique_ptr<Reconstructor> make_cgal_scale_space() { return std::make_unique<ScaleSpaceBaseline>(); }

}  // namespace dtsl::baselines
