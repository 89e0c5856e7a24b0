// cgal_advancing_front: CGAL's advancing front surface reconstruction (Cohen-Steiner & Da, 2004). It
// selects facets of the points' 3-D Delaunay triangulation, growing a surface from the most plausible
// one (smallest Delaunay sphere) across its boundary edges. It interpolates the input (every vertex is
// an input point), needs no normals, and leaves holes where the sampling is too sparse.
#include <CGAL/Advancing_front_surface_reconstruction.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <cmath>

#include "algorithms/baselines/baseline.hpp"
#include "algorithms/baselines/cgal_support.hpp"

namespace dtsl::baselines {
namespace {

struct AdvancingFrontOptions final : Options {
  double radius_ratio_bound = 5.0;
  double beta = 0.52;

  void visit(FieldVisitor& v) override {
    v.field("radius_ratio_bound", radius_ratio_bound,
            "a candidate triangle outside the beta-wedge is refused if its Delaunay radius exceeds this "
            "multiple of its neighbour's; lower leaves more holes, higher bridges gaps (CGAL default 5)");
    v.field("beta", beta,
            "half-angle (radians) of the wedge in which only the radius decides a candidate's plausibility "
            "(CGAL default 0.52, about 30 degrees)");
  }

  void check() const override {
    check_range("radius_ratio_bound", radius_ratio_bound, 1.0, 1e6);
    check_range("beta", beta, 0.0, M_PI / 2);
  }
};

class AdvancingFrontBaseline final : public PointsBaseline {
 public:
  AdvancingFrontBaseline() : PointsBaseline("cgal_advancing_front") {}
  Options& options() override { return options_; }

 protected:
  // A surface method: planar patches are fine (CGAL lifts a flat Delaunay triangulation with an extra
  // vertex), only collinear or too few points are refused.
  InputRequirements requirements() const override { return {10, false}; }

  TriangleMesh run(const PointCloud& cloud, const RunContext&, nlohmann::json& summary) override {
    using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
    std::vector<Kernel::Point_3> points;
    points.reserve(cloud.size());
    for (const Vec3& p : cloud.points) points.emplace_back(p.x(), p.y(), p.z());
    std::vector<std::array<std::size_t, 3>> facets;
    guarded_cgal_call(name(), [&] {
      CGAL::advancing_front_surface_reconstruction(points.begin(), points.end(), std::back_inserter(facets),
                                                   options_.radius_ratio_bound, options_.beta);
    });
    // Facets index the input points: the vertices are the exact input points.
    return interpolating_mesh(cloud.points, facets, summary);
  }

  std::string empty_hint() const override {
    return "the points may be too sparse: raise radius_ratio_bound (now " +
           format_number(options_.radius_ratio_bound) + ")";
  }

 private:
  AdvancingFrontOptions options_;
};

}  // namespace

std::unique_ptr<Reconstructor> make_cgal_advancing_front() { return std::make_unique<AdvancingFrontBaseline>(); }

}  // namespace dtsl::baselines
