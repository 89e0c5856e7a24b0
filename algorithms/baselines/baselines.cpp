#include "algorithms/baselines/baselines.hpp"

#include "algorithms/baselines/baseline.hpp"
#include "framework/pipeline/reconstructor.hpp"

namespace dtsl {

void register_baselines() {
  Registry<Reconstructor>& r = reconstructors();
  auto add = [&r](const char* name, const char* summary, std::unique_ptr<Reconstructor> (*make)()) {
    if (!r.contains(name)) r.add(name, summary, make);
  };
  add("pcl_poisson", "PCL Poisson surface reconstruction (octree, screened by point_weight); needs oriented normals",
      &baselines::make_pcl_poisson);
  add("pcl_mc_hoppe", "PCL marching cubes over Hoppe's signed distance to tangent planes; needs oriented normals",
      &baselines::make_pcl_mc_hoppe);
  add("pcl_mc_rbf",
      "PCL marching cubes over a cubic RBF interpolant with off-surface points; dense O(n^2) memory, "
      "refuses more than max_points",
      &baselines::make_pcl_mc_rbf);
  add("pcl_gp3", "PCL greedy projection triangulation: interpolates the points, leaves holes where sparse",
      &baselines::make_pcl_gp3);
  add("pcl_grid", "PCL grid projection: surface points projected along a normal-derived vector field",
      &baselines::make_pcl_grid);
}

}  // namespace dtsl
