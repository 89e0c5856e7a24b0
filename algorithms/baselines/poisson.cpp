// pcl_poisson: PCL's Poisson surface reconstruction (Kazhdan et al.; PCL ships PoissonRecon v4 with the
// screening term of point_weight).
#include <pcl/surface/poisson.h>

#include "algorithms/baselines/baseline.hpp"
#include "algorithms/baselines/pcl_convert.hpp"

namespace dtsl::baselines {
namespace {

struct PoissonOptions final : Options {
  int depth = 8;
  int min_depth = 5;
  double point_weight = 4.0;
  double scale = 1.1;
  double samples_per_node = 1.0;
  int solver_divide = 8;
  int iso_divide = 8;
  bool confidence = false;
  bool manifold = true;
  int degree = 2;
  NormalSourceOptions normals;

  void visit(FieldVisitor& v) override {
    v.field("depth", depth,
            "maximum octree depth: the finest cell is (scale x bounding cube) / 2^depth; 8 gives about "
            "0.009 in the [-1,1]^3 frame; each level costs ~4x time and memory (PCL default 8)");
    v.field("min_depth", min_depth, "coarsest octree depth the solver uses (PCL default 5)");
    v.field("point_weight", point_weight,
            "screening weight: how strongly the surface is pulled through the points; 0 gives the "
            "unscreened Poisson equation (PCL default 4)");
    v.field("scale", scale,
            "ratio of the reconstruction cube's diameter to the samples' bounding cube's (PCL default 1.1)");
    v.field("samples_per_node", samples_per_node,
            "minimum number of samples per octree node: 1-5 for clean data, 15-20 for noisy data "
            "(PCL default 1)");
    v.field("solver_divide", solver_divide,
            "depth from which the Laplacian is solved block-wise (saves memory); >= min_depth (PCL default 8)");
    v.field("iso_divide", iso_divide,
            "depth from which the iso-surface is extracted block-wise (saves memory); >= min_depth "
            "(PCL default 8)");
    v.field("confidence", confidence,
            "use the normals' lengths as confidence weights (ours are unit: no effect) (PCL default false)");
    v.field("manifold", manifold,
            "add a barycentre vertex to polygons so the output is manifold (PCL default true)");
    v.field("degree", degree, "degree of the B-spline basis, 1 to 5 (PCL default 2)");
    normals.visit(v);
  }

  void check() const override {
    check_range("depth", depth, 2, 12);
    check_range("min_depth", min_depth, 1, depth);
    check_non_negative("point_weight", point_weight);
    check_range("scale", scale, 1.0, 10.0);
    check_range("samples_per_node", samples_per_node, 1e-3, 1000.0);
    require(solver_divide >= min_depth && solver_divide <= 16, "solver_divide",
            "must be in [min_depth = " + std::to_string(min_depth) + ", 16], got " + std::to_string(solver_divide));
    require(iso_divide >= min_depth && iso_divide <= 16, "iso_divide",
            "must be in [min_depth = " + std::to_string(min_depth) + ", 16], got " + std::to_string(iso_divide));
    check_range("degree", degree, 1, 5);
    normals.check();
  }
};

class PoissonBaseline final : public PclBaseline {
 public:
  PoissonBaseline() : PclBaseline("pcl_poisson") {}
  Options& options() override { return options_; }

 protected:
  const NormalSourceOptions& normal_options() const override { return options_.normals; }
  InputRequirements requirements() const override { return {10, true}; }

  TriangleMesh run(const PointCloud& cloud, const RunContext& context, nlohmann::json& summary) override {
    const PoissonOptions& o = options_;
    PclCloud::Ptr input = to_pcl(cloud);
    PclCloud vertices;
    std::vector<pcl::Vertices> polygons;
    guarded_pcl_call(name(), [&] {
      pcl::Poisson<pcl::PointNormal> poisson;
      poisson.setDepth(o.depth);
      poisson.setMinDepth(o.min_depth);
      poisson.setPointWeight(static_cast<float>(o.point_weight));
      poisson.setScale(static_cast<float>(o.scale));
      poisson.setSamplesPerNode(static_cast<float>(o.samples_per_node));
      poisson.setSolverDivide(o.solver_divide);
      poisson.setIsoDivide(o.iso_divide);
      poisson.setConfidence(o.confidence);
      poisson.setManifold(o.manifold);
      poisson.setOutputPolygons(false);
      poisson.setDegree(o.degree);
      poisson.setThreads(std::max(1, context.threads));
      poisson.setInputCloud(input);
      poisson.reconstruct(vertices, polygons);
    });
    CleanupCounts counts;
    // Poisson's output is indexed and oriented outward already: no welding, no flip.
    TriangleMesh mesh = soup_to_mesh(to_soup(vertices, polygons), 0.0, false, &counts);
    summary["depth"] = o.depth;
    summary["cleanup"] = counts.to_json();
    return mesh;
  }

  std::string empty_hint() const override {
    return "check that the normals point consistently outward, or lower samples_per_node (now " +
           format_number(options_.samples_per_node) + ")";
  }

 private:
  PoissonOptions options_;
};

}  // namespace

std::unique_ptr<Reconstructor> make_pcl_poisson() { return std::make_unique<PoissonBaseline>(); }

}  // namespace dtsl::baselines
