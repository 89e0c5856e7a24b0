// The baselines as pipelines: PCL's surface reconstructors (pcl_poisson, pcl_mc_hoppe, pcl_mc_rbf,
// pcl_gp3, pcl_grid), CGAL's interpolating ones (cgal_advancing_front, cgal_scale_space), and `external`,
// any command-line reconstructor.
#pragma once

namespace dtsl {
/// Adds the baselines to reconstructors(). Idempotent.
void register_baselines();
}
