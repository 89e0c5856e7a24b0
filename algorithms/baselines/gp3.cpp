// pcl_gp3: PCL's greedy projection triangulation (Marton et al. 2009): grows a triangulation over the
// points themselves, projecting each point's neighbourhood onto its tangent plane. It interpolates the
// input (the mesh vertices are input points) and leaves holes where the sampling is too sparse.
#include <pcl/search/kdtree.h>
#include <pcl/surface/gp3.h>

#include <cmath>

#include "algorithms/baselines/baseline.hpp"
#include "algorithms/baselines/pcl_convert.hpp"

namespace dtsl::baselines {
namespace {

struct Gp3Options final : Options {
  double search_radius = 0.15;
  double mu = 4.0;
  int max_nearest_neighbors = 100;
  double max_surface_angle_deg = 45.0;
  double min_angle_deg = 10.0;
  double max_angle_deg = 120.0;
  bool normal_consistency = true;
  NormalSourceOptions normals;

  void visit(FieldVisitor& v) override {
    v.field("search_radius", search_radius,
            "longest edge allowed, in the [-1,1]^3 frame; 0.15 is 3-7 point spacings for 5k-30k points "
            "on a surface, so sparser regions still close (PCL: must be set by the user)");
    v.field("mu", mu,
            "a point connects to neighbours within mu x its nearest-neighbour distance (and within "
            "search_radius): adapts to the local density. PCL's tutorial uses 2.5, which leaves many "
            "holes in randomly sampled points (nearest distances vary a lot); 4 closes most of them");
    v.field("max_nearest_neighbors", max_nearest_neighbors,
            "neighbours considered per point (PCL default 100)");
    v.field("max_surface_angle_deg", max_surface_angle_deg,
            "neighbours whose normal deviates more than this from the point's are ignored (PCL default 45)");
    v.field("min_angle_deg", min_angle_deg, "smallest triangle angle aimed at (PCL default 10)");
    v.field("max_angle_deg", max_angle_deg, "largest triangle angle allowed (PCL default 120)");
    v.field("normal_consistency", normal_consistency,
            "the normals are consistently oriented, so GP3 need not flip them locally; true suits every "
            "normal source here (ground truth or MST-oriented) (PCL default false)");
    normals.visit(v);
  }

  void check() const override {
    check_range("search_radius", search_radius, 1e-6, 10.0);
    check_range("mu", mu, 1e-3, 100.0);
    check_range("max_nearest_neighbors", max_nearest_neighbors, 3, 10000);
    check_range("max_surface_angle_deg", max_surface_angle_deg, 0.0, 180.0);
    check_range("min_angle_deg", min_angle_deg, 0.0, 60.0);
    check_range("max_angle_deg", max_angle_deg, 60.0, 180.0);
    require(min_angle_deg < max_angle_deg, "min_angle_deg",
            "must be below max_angle_deg (" + format_number(max_angle_deg) + "), got " +
                format_number(min_angle_deg));
    normals.check();
  }
};

class Gp3Baseline final : public PclBaseline {
 public:
  Gp3Baseline() : PclBaseline("pcl_gp3") {}
  Options& options() override { return options_; }

 protected:
  const NormalSourceOptions& normal_options() const override { return options_.normals; }
  // A surface method: planar patches are fine, only collinear or too few points are refused.
  InputRequirements requirements() const override { return {10, false}; }

  TriangleMesh run(const PointCloud& cloud, const RunContext&, nlohmann::json& summary) override {
    const Gp3Options& o = options_;
    const double deg = M_PI / 180.0;
    PclCloud::Ptr input = to_pcl(cloud);
    pcl::search::KdTree<pcl::PointNormal>::Ptr tree(new pcl::search::KdTree<pcl::PointNormal>);
    std::vector<pcl::Vertices> polygons;
    guarded_pcl_call(name(), [&] {
      tree->setInputCloud(input);
      pcl::GreedyProjectionTriangulation<pcl::PointNormal> gp3;
      gp3.setSearchRadius(o.search_radius);
      gp3.setMu(o.mu);
      gp3.setMaximumNearestNeighbors(o.max_nearest_neighbors);
      gp3.setMaximumSurfaceAngle(o.max_surface_angle_deg * deg);
      gp3.setMinimumAngle(o.min_angle_deg * deg);
      gp3.setMaximumAngle(o.max_angle_deg * deg);
      gp3.setNormalConsistency(o.normal_consistency);
      gp3.setConsistentVertexOrdering(true);
      gp3.setSearchMethod(tree);
      gp3.setInputCloud(input);
      gp3.reconstruct(polygons);
    });
    CleanupCounts counts;
    // Polygons index the input points: the vertices are the exact (double) input points.
    TriangleMesh mesh = soup_to_mesh(to_soup(cloud, polygons), 0.0, false, &counts);
    summary["cleanup"] = counts.to_json();
    return mesh;
  }

  std::string empty_hint() const override {
    return "raise search_radius (now " + format_number(options_.search_radius) + ") or mu (now " +
           format_number(options_.mu) + ") above the point spacing";
  }

 private:
  Gp3Options options_;
};

}  // namespace

std::unique_ptr<Reconstructor> make_pcl_gp3() { return std::make_unique<Gp3Baseline>(); }

}  // namespace dtsl::baselines
