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
  add("cgal_advancing_front",
      "CGAL advancing front: grows a surface over Delaunay facets through the points; no normals, "
      "leaves holes where sparse",
      &baselines::make_cgal_advancing_front);
  add("cgal_scale_space",
      "CGAL scale space: meshes smoothed points (advancing front or alpha shape), keeps the input points; "
      "no normals",
      &baselines::make_cgal_scale_space);
  add("external",
      "any command-line reconstructor: writes the points to {in}, runs `command`, reads the mesh from {out}",
      &baselines::make_external);
}

}  // namespace dtsl
