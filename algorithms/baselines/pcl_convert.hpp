// Private to algorithms/baselines: conversions between dtsl's types and PCL's. Included only by the
// .cpp files that call PCL (they need PCL's headers anyway).
#pragma once

#include <pcl/Vertices.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <vector>

#include "algorithms/baselines/baseline.hpp"

namespace dtsl::baselines {

using PclCloud = pcl::PointCloud<pcl::PointNormal>;

/// Points and normals (one per point, required) in single precision, as PCL's reconstructors take them.
PclCloud::Ptr to_pcl(const PointCloud& cloud);

/// Vertices and polygons from a PCL reconstructor's (points, polygons) output.
PolygonSoup to_soup(const PclCloud& vertices, const std::vector<pcl::Vertices>& polygons);

/// Polygons indexing `cloud` (a mesh construction such as greedy projection) as a soup over its points.
PolygonSoup to_soup(const PointCloud& cloud, const std::vector<pcl::Vertices>& polygons);

}  // namespace dtsl::baselines
