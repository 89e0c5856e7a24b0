// PCL's surface reconstructors as pipelines: pcl_poisson, pcl_mc_hoppe, pcl_mc_rbf, pcl_gp3, pcl_grid.
#pragma once

namespace dtsl {
/// Adds the baselines to reconstructors(). Idempotent.
void register_baselines();
}
