#include "framework/render/rasterizer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dtsl::render {

namespace {

/// Calls visit(x, y, depth) for every pixel whose centre the screen triangle abc covers, depth
/// interpolated linearly (orthographic camera).
template <typename Visit>
void fill_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, int W, int H,
                   Visit visit) {
  const double area = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
  if (std::abs(area) < 1e-12) return;
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
      visit(x, y, w0 * a.z() + w1 * b.z() + w2 * c.z());
    }
}

}  // namespace

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

    fill_triangle(screen[f[0]], screen[f[1]], screen[f[2]], W, H, [&](int x, int y, double depth) {
      if (test_and_set(x, y, depth)) image_.at(x, y) = colour;
    });
  }
}

void Canvas::draw_depth(const TriangleMesh& mesh, const Camera& camera, double offset) {
  std::vector<Eigen::Vector3d> screen(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) screen[i] = camera.project(mesh.vertices[i]);
  const long long n = static_cast<long long>(mesh.vertices.size());
  for (const Face& f : mesh.faces) {
    if (f[0] < 0 || f[1] < 0 || f[2] < 0 || f[0] >= n || f[1] >= n || f[2] >= n) continue;
    fill_triangle(screen[f[0]], screen[f[1]], screen[f[2]], image_.width(), image_.height(),
                  [&](int x, int y, double depth) { test_and_set(x, y, depth - offset); });
  }
}

void Canvas::draw_lines(const std::vector<std::array<Vec3, 2>>& segments, const Camera& camera, const LineStyle& s) {
  const int W = image_.width(), H = image_.height();
  const double half = 0.5 * std::max(s.width, 1.0);
  for (const std::array<Vec3, 2>& seg : segments) {
    const Eigen::Vector3d a = camera.project(seg[0]), b = camera.project(seg[1]);
    if (!a.allFinite() || !b.allFinite()) continue;
    // Step one pixel at a time along the longer screen axis (DDA), from the pixel holding one end to
    // the pixel holding the other; across it, cover `width` pixels centred on the line.
    const double dx = b.x() - a.x(), dy = b.y() - a.y();
    const bool steep = std::abs(dy) > std::abs(dx);
    const double a_major = steep ? a.y() : a.x(), b_major = steep ? b.y() : b.x();
    const double a_minor = steep ? a.x() : a.y(), b_minor = steep ? b.x() : b.y();
    const int limit_major = steep ? H : W, limit_minor = steep ? W : H;
    const int m0 = static_cast<int>(std::floor(std::min(a_major, b_major)));
    const int m1 = static_cast<int>(std::floor(std::max(a_major, b_major)));
    const double span = b_major - a_major;
    for (int m = std::max(m0, 0); m <= std::min(m1, limit_major - 1); ++m) {
      // The parameter where the line crosses this row/column's centre; in an end's own row/column, the
      // end itself, so that both end pixels are drawn.
      const double t = m == static_cast<int>(std::floor(a_major))   ? 0.0
                       : m == static_cast<int>(std::floor(b_major)) ? 1.0
                                                                    : std::clamp((m + 0.5 - a_major) / span, 0.0, 1.0);
      const double minor = a_minor + t * (b_minor - a_minor);
      const double depth = a.z() + t * (b.z() - a.z()) + s.depth_bias;
      const int n0 = static_cast<int>(std::floor(minor - half + 0.5)), n1 = static_cast<int>(std::floor(minor + half - 0.5));
      for (int k = std::max(n0, 0); k <= std::min(std::max(n1, n0), limit_minor - 1); ++k) {
        const int x = steep ? k : m, y = steep ? m : k;
        const bool hidden = depth < depth_[static_cast<std::size_t>(y) * W + x];
        const double alpha = hidden ? s.hidden_alpha : s.alpha;
        if (alpha > 0.0) image_.set(x, y, s.colour, alpha);
      }
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
