// pcl_grid: PCL's grid projection (Li et al. 2010): a vector field from the normals of the points near
// each cell of a uniform grid, surface points found by binary search along it, one quad per crossed
// grid edge. Slow: its cost grows with the points x (2 padding_size + 1)^3 x max_binary_search_level.
//
// Facts about PCL 1.13's GridProjection that the options account for:
// - it divides the points by their largest bounding-box side when that exceeds 1 and works in those
//   units: our `resolution` is in the [-1,1]^3 frame and converted, so it means what it says;
// - it allocates a flag per cell of its whole bounding grid, (side / resolution + 10)^3 ints, indexed
//   with int arithmetic: a too fine resolution exhausts memory or overflows, so max_grid_cells refuses it;
// - it needs more than 10 points in a cell's (2 padding_size + 1)^3 neighbourhood to place a surface
//   point there, so a resolution far below the point spacing yields nothing;
// - nearest_neighbors is stored but unused: its k-nearest-neighbour code path is commented out;
// - it emits one vertex per quad corner: we weld them;
// - its quads' winding is arbitrary: we orient each triangle by the nearest input point's normal.
#include <pcl/search/kdtree.h>
#include <pcl/surface/grid_projection.h>

#include <cmath>

#include "algorithms/baselines/baseline.hpp"
#include "algorithms/baselines/pcl_convert.hpp"
#include "framework/core/error.hpp"

namespace dtsl::baselines {
namespace {

struct GridOptions final : Options {
  double resolution = 0.03;
  int padding_size = 3;
  int nearest_neighbors = 50;
  int max_binary_search_level = 10;
  int max_grid_cells = 16777216;
  NormalSourceOptions normals;

  void visit(FieldVisitor& v) override {
    v.field("resolution", resolution,
            "grid cell size in the [-1,1]^3 frame: the best of 0.02-0.04 on fandisk, bunny (6k points) "
            "and armadillo (25k); below the point spacing cells miss the >10 neighbours PCL requires and "
            "the surface tears (PCL default 0.001 in its units, far too fine here)");
    v.field("padding_size", padding_size,
            "cells around each occupied cell that are filled and searched; the time grows as "
            "(2 padding_size + 1)^3 (PCL default 3)");
    v.field("nearest_neighbors", nearest_neighbors,
            "k of PCL's k-nearest-neighbour variant, which PCL 1.13 does not call: no effect "
            "(PCL default 50)");
    v.field("max_binary_search_level", max_binary_search_level,
            "bisection steps when projecting a grid point onto the surface (PCL default 10)");
    v.field("max_grid_cells", max_grid_cells,
            "refuse a resolution whose bounding grid, (side / resolution + 10)^3 cells, exceeds this: "
            "PCL allocates and scans all of them (default 256^3)");
    normals.visit(v);
  }

  void check() const override {
    check_range("resolution", resolution, 1e-4, 2.0);
    check_range("padding_size", padding_size, 1, 6);
    check_range("nearest_neighbors", nearest_neighbors, 1, 10000);
    check_range("max_binary_search_level", max_binary_search_level, 1, 30);
    check_range("max_grid_cells", max_grid_cells, 1000, 1000000000);
    normals.check();
  }
};

class GridBaseline final : public PclBaseline {
 public:
  GridBaseline() : PclBaseline("pcl_grid") {}
  Options& options() override { return options_; }

 protected:
  const NormalSourceOptions& normal_options() const override { return options_.normals; }
  // Like greedy projection it follows the points' surface, so planar patches are acceptable.
  InputRequirements requirements() const override { return {11, false}; }

  // PCL's scale factor and cell count for this input (getBoundingBox in grid_projection.hpp).
  double pcl_scale(const PointCloud& cloud) const {
    const double side = bounding_box(cloud.points).extent().maxCoeff();
    return side > 1.0 ? side : 1.0;
  }
  double cells_per_axis(const PointCloud& cloud) const {
    const double side = bounding_box(cloud.points).extent().maxCoeff();
    return std::floor(side / options_.resolution) + 12.0;  // PCL pads 5 cells per side, +2 for rounding
  }

  void check_input(const PointCloud& cloud) const override {
    const double n = cells_per_axis(cloud);
    const double cells = n * n * n;
    if (cells > options_.max_grid_cells)
      throw AlgorithmError("pcl_grid: resolution " + format_number(options_.resolution) + " gives a grid of " +
                           format_number(n) + "^3 = " + format_number(cells) + " cells, above max_grid_cells = " +
                           std::to_string(options_.max_grid_cells) +
                           "; raise the option resolution (or max_grid_cells if memory allows)");
  }

  TriangleMesh run(const PointCloud& cloud, const RunContext&, nlohmann::json& summary) override {
    const GridOptions& o = options_;
    PclCloud::Ptr input = to_pcl(cloud);
    pcl::search::KdTree<pcl::PointNormal>::Ptr tree(new pcl::search::KdTree<pcl::PointNormal>);
    PclCloud vertices;
    std::vector<pcl::Vertices> polygons;
    const double scale = pcl_scale(cloud);
    guarded_pcl_call(name(), [&] {
      tree->setInputCloud(input);
      pcl::GridProjection<pcl::PointNormal> grid;
      grid.setResolution(o.resolution / scale);
      grid.setPaddingSize(o.padding_size);
      grid.setNearestNeighborNum(o.nearest_neighbors);
      grid.setMaxBinarySearchLevel(o.max_binary_search_level);
      grid.setSearchMethod(tree);
      grid.setInputCloud(input);
      grid.reconstruct(vertices, polygons);
    });
    // Quad corners are copies of the same stored surface point: weld at float rounding level.
    const double tolerance = 1e-6 * o.resolution;
    CleanupCounts counts;
    TriangleMesh mesh = soup_to_mesh(to_soup(vertices, polygons), tolerance, false, &counts);
    // PCL winds its quads arbitrarily (the signed volume of a sphere comes out near 0): orient each
    // triangle like the normal of the input point nearest its centroid.
    std::size_t flipped = 0;
    guarded_pcl_call(name(), [&] {
      pcl::Indices nearest(1);
      std::vector<float> sqr_distances(1);
      for (Face& f : mesh.faces) {
        const Vec3& a = mesh.vertices[f[0]];
        const Vec3& b = mesh.vertices[f[1]];
        const Vec3& c = mesh.vertices[f[2]];
        pcl::PointNormal q;
        q.getVector3fMap() = ((a + b + c) / 3.0).cast<float>();
        if (tree->nearestKSearch(q, 1, nearest, sqr_distances) < 1) continue;
        if ((b - a).cross(c - a).dot(cloud.normals[nearest[0]]) < 0.0) {
          std::swap(f[1], f[2]);
          ++flipped;
        }
      }
    });
    const double n = cells_per_axis(cloud);
    summary["grid_cells"] = n * n * n;
    summary["cleanup"] = counts.to_json();
    summary["triangles_reoriented"] = flipped;
    return mesh;
  }

  std::string empty_hint() const override {
    return "resolution " + format_number(options_.resolution) +
           " is probably below the point spacing (PCL needs > 10 points near a cell): raise resolution "
           "or padding_size";
  }

 private:
  GridOptions options_;
};

}  // namespace

std::unique_ptr<Reconstructor> make_pcl_grid() { return std::make_unique<GridBaseline>(); }

}  // namespace dtsl::baselines
