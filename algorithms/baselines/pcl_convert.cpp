#include "algorithms/baselines/pcl_convert.hpp"

#include "framework/core/error.hpp"

namespace dtsl::baselines {

PclCloud::Ptr to_pcl(const PointCloud& cloud) {
  if (!cloud.has_normals()) throw Error("to_pcl: the cloud has no normals (programming error)");
  PclCloud::Ptr out(new PclCloud);
  out->resize(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    pcl::PointNormal& p = (*out)[i];
    p.getVector3fMap() = cloud.points[i].cast<float>();
    p.getNormalVector3fMap() = cloud.normals[i].cast<float>();
    p.curvature = 0.0f;
  }
  out->width = static_cast<std::uint32_t>(cloud.size());
  out->height = 1;
  out->is_dense = true;
  return out;
}

namespace {
std::vector<std::vector<int>> polygons_of(const std::vector<pcl::Vertices>& polygons) {
  std::vector<std::vector<int>> out(polygons.size());
  for (std::size_t i = 0; i < polygons.size(); ++i)
    out[i].assign(polygons[i].vertices.begin(), polygons[i].vertices.end());
  return out;
}
}  // namespace

PolygonSoup to_soup(const PclCloud& vertices, const std::vector<pcl::Vertices>& polygons) {
  PolygonSoup soup;
  soup.vertices.reserve(vertices.size());
  for (const pcl::PointNormal& p : vertices) soup.vertices.push_back(p.getVector3fMap().cast<double>());
  soup.polygons = polygons_of(polygons);
  return soup;
}

PolygonSoup to_soup(const PointCloud& cloud, const std::vector<pcl::Vertices>& polygons) {
  PolygonSoup soup;
  soup.vertices = cloud.points;
  soup.polygons = polygons_of(polygons);
  return soup;
}

}  // namespace dtsl::baselines
