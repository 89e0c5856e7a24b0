#include "framework/render/rasterizer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dtsl::render {

Canvas::Canvas(int width, int height, Rgb background)
    : image_(width, height, background),
      depth_(static_cast<std::size_t>(image_.width()) * image_.height(), -std::numeric_limits<double>::infinity()) {}

bool Canvas::test_and_set(int x, int y, double depth) {
  double& d = depth_[static_cast<std::size_t>(y) * image_.width() + x];
  if (depth <= d) return false;
  d = depth;
  return true;
}

void Canvas::draw_mesh(const TriangleMesh& mesh, const Camera& camera, const ShadingOptions& s) {
  // The light comes from the viewer's upper left, fixed in camera space.
  const Vec3 light = (-0.45 * camera.right() + 0.55 * camera.up() + 0.70 * camera.towards_viewer()).normalized();
  std::vector<Eigen::Vector3d> screen(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) screen[i] = camera.project(mesh.vertices[i]);
  const int W = image_.width(), H = image_.height();
  for (const Face& f : mesh.faces) {
    if (f[0] < 0 || f[1] < 0 || f[2] < 0) continue;
    const std::size_t n = mesh.vertices.size();
    if (static_cast<std::size_t>(f[0]) >= n || static_cast<std::size_t>(f[1]) >= n || static_cast<std::size_t>(f[2]) >= n)
      continue;
    Vec3 normal = (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]);
    const double len = normal.norm();
    if (!(len > 0)) continue;
    normal /= len;
    const bool front = normal.dot(camera.towards_viewer()) >= 0;
    if (!front) normal = -normal;
    const double shade = s.ambient + (1.0 - s.ambient) * std::max(0.0, normal.dot(light));
    const Rgb base = front ? s.front : s.back;
    const Rgb colour = rgb(base.r / 255.0 * shade, base.g / 255.0 * shade, base.b / 255.0 * shade);

    const Eigen::Vector3d &a = screen[f[0]], &b = screen[f[1]], &c = screen[f[2]];
    const double area = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    if (std::abs(area) < 1e-12) continue;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}))));
    const int x1 = std::min(W - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}))));
    const int y1 = std::min(H - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5, py = y + 0.5;
        const double w0 = ((b.x() - px) * (c.y() - py) - (b.y() - py) * (c.x() - px)) / area;
        const double w1 = ((c.x() - px) * (a.y() - py) - (c.y() - py) * (a.x() - px)) / area;
        const double w2 = 1.0 - w0 - w1;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        if (test_and_set(x, y, w0 * a.z() + w1 * b.z() + w2 * c.z())) image_.at(x, y) = colour;
      }
  }
}

void Canvas::draw_points(const std::vector<Vec3>& points, const Camera& camera, const ShadingOptions& s) {
  if (points.empty()) return;
  std::vector<Eigen::Vector3d> screen(points.size());
  double dmin = std::numeric_limits<double>::infinity(), dmax = -dmin;
  for (std::size_t i = 0; i < points.size(); ++i) {
    screen[i] = camera.project(points[i]);
    dmin = std::min(dmin, screen[i].z()), dmax = std::max(dmax, screen[i].z());
  }
  const double span = std::max(dmax - dmin, 1e-12);
  const double r = std::max(s.point_radius, 0.5);
  const int ri = static_cast<int>(std::ceil(r));
  for (const Eigen::Vector3d& p : screen) {
    const double t = (dmax - p.z()) / span;  // 0 near, 1 far
    const Rgb colour = rgb((s.point_near.r + t * (s.point_far.r - s.point_near.r)) / 255.0,
                           (s.point_near.g + t * (s.point_far.g - s.point_near.g)) / 255.0,
                           (s.point_near.b + t * (s.point_far.b - s.point_near.b)) / 255.0);
    const int cx = static_cast<int>(std::floor(p.x())), cy = static_cast<int>(std::floor(p.y()));
    for (int dy = -ri; dy <= ri; ++dy)
      for (int dx = -ri; dx <= ri; ++dx) {
        const int x = cx + dx, y = cy + dy;
        if (!image_.inside(x, y)) continue;
        if (std::hypot(x + 0.5 - p.x(), y + 0.5 - p.y()) > r) continue;
        if (test_and_set(x, y, p.z())) image_.at(x, y) = colour;
      }
  }
}

}  // namespace dtsl::render
