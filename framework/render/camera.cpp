#include "framework/render/camera.hpp"

#include <algorithm>
#include <cmath>

#include "framework/core/error.hpp"

namespace dtsl::render {

void ViewOptions::check() const {
  if (!(elevation_deg > -90.0 && elevation_deg < 90.0)) throw ConfigError("view.elevation_deg: must be in (-90, 90)");
  if (up != 'x' && up != 'y' && up != 'z') throw ConfigError("view.up: must be x, y or z");
  if (!(zoom >= 1.0 && zoom <= 100.0)) throw ConfigError("view.zoom: must be in [1, 100]");
  if (!(margin >= 0.0 && margin < 0.45)) throw ConfigError("view.margin: must be in [0, 0.45)");
  if (!std::isfinite(azimuth_deg)) throw ConfigError("view.azimuth_deg: must be finite");
}

Camera::Camera(const BoundingBox& box_in, int width, int height, const ViewOptions& view) {
  view.check();
  BoundingBox box = box_in;
  if (!box.valid()) box.extend(Vec3::Zero());
  // Up axis U and two horizontal axes: A points at the viewer at azimuth 0 (the "front"), B to its right.
  Vec3 U, A, B;
  switch (view.up) {
    case 'x': U = Vec3::UnitX(), A = Vec3::UnitZ(), B = Vec3::UnitY(); break;
    case 'z': U = Vec3::UnitZ(), A = -Vec3::UnitY(), B = Vec3::UnitX(); break;
    default: U = Vec3::UnitY(), A = Vec3::UnitZ(), B = Vec3::UnitX(); break;
  }
  const double az = view.azimuth_deg * M_PI / 180.0, el = view.elevation_deg * M_PI / 180.0;
  eye_ = (std::cos(el) * (std::cos(az) * A + std::sin(az) * B) + std::sin(el) * U).normalized();
  right_ = U.cross(eye_).normalized();
  up_ = eye_.cross(right_).normalized();
  centre_ = box.center();

  double xmin = 0, xmax = 0, ymin = 0, ymax = 0;
  for (int c = 0; c < 8; ++c) {
    const Vec3 p((c & 1) ? box.max.x() : box.min.x(), (c & 2) ? box.max.y() : box.min.y(),
                 (c & 4) ? box.max.z() : box.min.z());
    const double x = (p - centre_).dot(right_), y = (p - centre_).dot(up_);
    xmin = std::min(xmin, x), xmax = std::max(xmax, x), ymin = std::min(ymin, y), ymax = std::max(ymax, y);
  }
  const double usable_w = width * (1.0 - 2.0 * view.margin), usable_h = height * (1.0 - 2.0 * view.margin);
  const double w = std::max(xmax - xmin, 1e-12), h = std::max(ymax - ymin, 1e-12);
  scale_ = std::min(usable_w / w, usable_h / h) * view.zoom;
  // Centre the box's projection (not its centre point) in the image.
  const double mx = 0.5 * (xmin + xmax), my = 0.5 * (ymin + ymax);
  cx_ = 0.5 * width - mx * scale_ * (view.zoom > 1.0 ? 0.0 : 1.0);
  cy_ = 0.5 * height + my * scale_ * (view.zoom > 1.0 ? 0.0 : 1.0);
}

Eigen::Vector3d Camera::project(const Vec3& p) const {
  const Vec3 d = p - centre_;
  return {cx_ + d.dot(right_) * scale_, cy_ - d.dot(up_) * scale_, d.dot(eye_)};
}

}  // namespace dtsl::render
