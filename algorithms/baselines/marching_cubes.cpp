// pcl_mc_hoppe and pcl_mc_rbf: PCL's marching cubes over two implicit functions of oriented points —
// Hoppe et al.'s signed distance to the nearest point's tangent plane, and Carr et al.'s radial basis
// function interpolant with off-surface points.
//
// Facts about PCL 1.13's MarchingCubes that the options below account for:
// - the grid spans the points' bounding box enlarged by percentage_extend_grid, with the same number of
//   nodes on every axis, and the outermost layer of cells is never polygonised: with PCL's default
//   extension 0 the surface is cut open where it touches the box, hence our default 0.1;
// - it emits one vertex per triangle corner (a triangle soup): we weld coincident corners;
// - MarchingCubesHoppe compares the *squared* nearest-point distance with dist_ignore: we pass the
//   square, so our dist_ignore is a distance;
// - MarchingCubesRBF solves its dense 2n x 2n system with a full-pivoting LU, unblocked and single
//   threaded (minutes at n = 2000). By default we solve the same system with a blocked partial-pivoting
//   LU (same interpolant, ~10x faster) and evaluate the grid in parallel; rbf_solver = "pcl" keeps
//   PCL's own code.
#include <pcl/search/kdtree.h>
#include <pcl/surface/marching_cubes_hoppe.h>
#include <pcl/surface/marching_cubes_rbf.h>

#include <Eigen/LU>
#include <cmath>

#include "algorithms/baselines/baseline.hpp"
#include "algorithms/baselines/pcl_convert.hpp"
#include "framework/core/error.hpp"

namespace dtsl::baselines {
namespace {

// PCL's marching cubes triangles already face outward (towards larger function values), like
// Poisson's: checked by the signed volume in tests/baselines.
constexpr bool kFlipMarchingCubes = false;

// Options both marching cubes share.
struct GridOptions {
  explicit GridOptions(int resolution) : grid_resolution(resolution) {}
  int grid_resolution;
  double iso_level = 0.0;
  double percentage_extend_grid = 0.1;

  void visit(FieldVisitor& v) {
    v.field("grid_resolution", grid_resolution,
            "grid nodes per axis over the extended bounding box (cells of 2.2 / grid_resolution in the "
            "[-1,1]^3 frame), near the point spacing: 100 for pcl_mc_hoppe (0.022, 5k-30k points), 64 "
            "for pcl_mc_rbf (0.034, at most max_points points; its cost is nodes x 2n) (PCL default 32)");
    v.field("iso_level", iso_level,
            "level of the implicit function that is extracted, in [0, 1); 0 is the surface, a positive "
            "value offsets it outward (PCL default 0)");
    v.field("percentage_extend_grid", percentage_extend_grid,
            "the grid extends the bounding box by this fraction of its size (half on each side); PCL "
            "never polygonises the outermost cells, so below ~0.07 at 64 nodes the surface is cut open "
            "at the box (PCL default 0)");
  }
  void check() const {
    check_range("grid_resolution", grid_resolution, 8, 256);
    require(iso_level >= 0.0 && iso_level < 1.0, "iso_level",
            "must be in [0, 1) (PCL's marching cubes rejects other values), got " + format_number(iso_level));
    check_range("percentage_extend_grid", percentage_extend_grid, 0.0, 1.0);
  }
};

struct HoppeOptions final : Options {
  GridOptions grid{100};
  double dist_ignore = 0.0;
  NormalSourceOptions normals;

  void visit(FieldVisitor& v) override {
    grid.visit(v);
    v.field("dist_ignore", dist_ignore,
            "grid nodes farther than this from every point are left undefined, which opens the surface "
            "over holes in the data instead of bridging them; 0 disables it and keeps the surface closed "
            "(PCL default: disabled)");
    normals.visit(v);
  }
  void check() const override {
    grid.check();
    check_range("dist_ignore", dist_ignore, 0.0, 10.0);
    normals.check();
  }
};

struct RbfOptions final : Options {
  GridOptions grid{64};
  double off_surface_displacement = 0.05;
  int max_points = 4000;
  std::string rbf_solver = "partial_piv_lu";
  NormalSourceOptions normals;

  void visit(FieldVisitor& v) override {
    grid.visit(v);
    v.field("off_surface_displacement", off_surface_displacement,
            "distance along the normal of the off-surface constraint points (value = that distance); "
            "keep it below half the thinnest part's thickness (PCL default 0.1 in the input's units)");
    v.field("max_points", max_points,
            "refuse inputs with more (distinct) points: the RBF system is dense, 2n x 2n, so n = 4000 "
            "needs 512 MiB and about 35 s on one core; n = 8000 would need 2 GiB and ~8x the time");
    v.field("rbf_solver", rbf_solver,
            "partial_piv_lu: the same system solved by Eigen's blocked LU (fast); pcl: PCL's own "
            "full-pivoting LU (exactly PCL, ~10x slower, twice the memory)");
    normals.visit(v);
  }
  void check() const override {
    grid.check();
    check_range("off_surface_displacement", off_surface_displacement, 1e-6, 1.0);
    check_range("max_points", max_points, 10, 20000);
    check_one_of("rbf_solver", rbf_solver, {"partial_piv_lu", "pcl"});
    normals.check();
  }
};

// MarchingCubesRBF with its voxelisation (solve + grid evaluation) optionally replaced by a faster
// computation of the same function.
class FastMarchingCubesRBF final : public pcl::MarchingCubesRBF<pcl::PointNormal> {
 public:
  bool use_pcl_solver = false;
  int threads = 1;
  double rcond = -1.0;  // reciprocal condition estimate of the system (fast solver only)

 protected:
  void voxelizeData() override {
    if (use_pcl_solver) {
      pcl::MarchingCubesRBF<pcl::PointNormal>::voxelizeData();
      return;
    }
    const Eigen::Index n = static_cast<Eigen::Index>(input_->size());
    const double eps = off_surface_epsilon_;
    std::vector<Eigen::Vector3d> centres(2 * n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Vector3d p = (*input_)[i].getVector3fMap().cast<double>();
      const Eigen::Vector3d nrm = (*input_)[i].getNormalVector3fMap().cast<double>();
      centres[i] = p;
      centres[i + n] = p + nrm * eps;
    }
    const Eigen::Index m = 2 * n;
    Eigen::MatrixXd a(m, m);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (Eigen::Index col = 0; col < m; ++col)
      for (Eigen::Index row = 0; row < m; ++row) {
        const double r = (centres[row] - centres[col]).norm();
        a(row, col) = r * r * r;
      }
    Eigen::VectorXd d(m);
    d.head(n).setZero();
    d.tail(n).setConstant(eps);

    const int saved_threads = Eigen::nbThreads();
    Eigen::setNbThreads(threads);
    Eigen::VectorXd w;
    {
      Eigen::PartialPivLU<Eigen::Ref<Eigen::MatrixXd>> lu(a);  // in place: no second copy
      rcond = lu.rcond();
      w = lu.solve(d);
    }
    Eigen::setNbThreads(saved_threads);
    if (!w.allFinite())
      throw AlgorithmError("pcl_mc_rbf: the RBF system is singular (rcond " + format_number(rcond) + ")");

    const int rx = res_x_, ry = res_y_, rz = res_z_;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
    for (int x = 0; x < rx; ++x)
      for (int y = 0; y < ry; ++y)
        for (int z = 0; z < rz; ++z) {
          const Eigen::Vector3d point =
              (size_voxel_ * Eigen::Array3f(x, y, z) + lower_boundary_).matrix().cast<double>();
          double f = 0.0;
          for (Eigen::Index k = 0; k < m; ++k) {
            const double r = (centres[k] - point).norm();
            f += w[k] * r * r * r;
          }
          grid_[x * ry * rz + y * rz + z] = static_cast<float>(f);
        }
  }
};

template <class MarchingCubes>
TriangleMesh extract(const std::string& method, MarchingCubes& mc, const GridOptions& o, const PointCloud& cloud,
                     nlohmann::json& summary) {
  PclCloud::Ptr input = to_pcl(cloud);
  pcl::search::KdTree<pcl::PointNormal>::Ptr tree(new pcl::search::KdTree<pcl::PointNormal>);
  PclCloud vertices;
  std::vector<pcl::Vertices> polygons;
  guarded_pcl_call(method, [&] {
    tree->setInputCloud(input);
    mc.setGridResolution(o.grid_resolution, o.grid_resolution, o.grid_resolution);
    mc.setIsoLevel(static_cast<float>(o.iso_level));
    mc.setPercentageExtendGrid(static_cast<float>(o.percentage_extend_grid));
    mc.setSearchMethod(tree);
    mc.setInputCloud(input);
    mc.reconstruct(vertices, polygons);
  });
  // Weld corners closer than 1e-4 of the smallest voxel edge: far above float rounding (the same edge
  // crossing is computed twice, in opposite directions), far below any genuine vertex spacing.
  const Vec3 extent = bounding_box(cloud.points).extent() * (1.0 + o.percentage_extend_grid);
  const double voxel = extent.minCoeff() / o.grid_resolution;
  const double tolerance = std::max(1e-4 * voxel, 1e-7);
  CleanupCounts counts;
  TriangleMesh mesh = soup_to_mesh(to_soup(vertices, polygons), tolerance, kFlipMarchingCubes, &counts);
  summary["grid"] = {o.grid_resolution, o.grid_resolution, o.grid_resolution};
  summary["voxel_size"] = (extent / o.grid_resolution).maxCoeff();
  summary["weld_tolerance"] = tolerance;
  summary["cleanup"] = counts.to_json();
  return mesh;
}

class HoppeBaseline final : public PclBaseline {
 public:
  HoppeBaseline() : PclBaseline("pcl_mc_hoppe") {}
  Options& options() override { return options_; }

 protected:
  const NormalSourceOptions& normal_options() const override { return options_.normals; }
  InputRequirements requirements() const override { return {10, true}; }

  TriangleMesh run(const PointCloud& cloud, const RunContext&, nlohmann::json& summary) override {
    pcl::MarchingCubesHoppe<pcl::PointNormal> mc;
    const double d = options_.dist_ignore;
    mc.setDistanceIgnore(d > 0.0 ? static_cast<float>(d * d) : -1.0f);  // PCL compares squared distances
    return extract(name(), mc, options_.grid, cloud, summary);
  }

  std::string empty_hint() const override {
    return "the zero level set missed the grid: check the normals, iso_level (" +
           format_number(options_.grid.iso_level) + ") and dist_ignore (" + format_number(options_.dist_ignore) + ")";
  }

 private:
  HoppeOptions options_;
};

class RbfBaseline final : public PclBaseline {
 public:
  RbfBaseline() : PclBaseline("pcl_mc_rbf") {}
  Options& options() override { return options_; }

 protected:
  const NormalSourceOptions& normal_options() const override { return options_.normals; }
  InputRequirements requirements() const override { return {10, true}; }

  void check_input(const PointCloud& cloud) const override {
    const std::size_t n = cloud.size();
    if (n > static_cast<std::size_t>(options_.max_points)) {
      const double mib = 8.0 * (2.0 * n) * (2.0 * n) / (1024.0 * 1024.0);
      throw AlgorithmError("pcl_mc_rbf: " + std::to_string(n) + " distinct points exceed max_points = " +
                           std::to_string(options_.max_points) + ": MarchingCubesRBF solves a dense " +
                           std::to_string(2 * n) + " x " + std::to_string(2 * n) + " system (" +
                           format_number(std::round(mib)) +
                           " MiB, cubic time); subsample the input or raise the option max_points");
    }
  }

  TriangleMesh run(const PointCloud& cloud, const RunContext& context, nlohmann::json& summary) override {
    FastMarchingCubesRBF mc;
    mc.use_pcl_solver = options_.rbf_solver == "pcl";
    mc.threads = std::max(1, context.threads);
    mc.setOffSurfaceDisplacement(static_cast<float>(options_.off_surface_displacement));
    TriangleMesh mesh = extract(name(), mc, options_.grid, cloud, summary);
    summary["rbf_system_size"] = 2 * cloud.size();
    summary["rbf_solver"] = options_.rbf_solver;
    if (mc.rcond >= 0.0) summary["rbf_rcond"] = mc.rcond;
    return mesh;
  }

  std::string empty_hint() const override {
    return "the interpolant has no zero crossing on the grid: check the normals and off_surface_displacement (" +
           format_number(options_.off_surface_displacement) + ")";
  }

 private:
  RbfOptions options_;
};

}  // namespace

std::unique_ptr<Reconstructor> make_pcl_mc_hoppe() { return std::make_unique<HoppeBaseline>(); }
std::unique_ptr<Reconstructor> make_pcl_mc_rbf() { return std::make_unique<RbfBaseline>(); }

}  // namespace dtsl::baselines
