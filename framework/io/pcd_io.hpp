// Private to framework/io: PCD through PCL. Its own target (dtsl_io_pcd) is the only place PCL headers
// are included, so nothing here mentions PCL types.
#pragma once

#include <string>

#include "framework/core/types.hpp"

namespace dtsl::io_detail {

/// x y z and, if all three are present, normal_x normal_y normal_z of any numeric type.
PointCloud read_pcd(const std::string& path);

/// Fields x y z [normal_x normal_y normal_z] as float32, PCL's own convention (pcl::PointXYZ,
/// pcl::PointNormal), so PCL tools read the file; coordinates keep about 7 significant digits.
void write_pcd(const std::string& path, const PointCloud& cloud, bool binary);

}  // namespace dtsl::io_detail
