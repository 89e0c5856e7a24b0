// An orthographic camera looking at a bounding box from a direction given by azimuth and elevation
// about a chosen "up" axis, so a model is drawn upright whatever its axis convention.
#pragma once

#include <Eigen/Core>

#include "framework/core/types.hpp"

namespace dtsl::render {

struct ViewOptions {
  double azimuth_deg = 30.0;    ///< rotation about the up axis; 0 looks at the model's front
  double elevation_deg = 20.0;  ///< above the horizontal plane, in (-90, 90)
  char up = 'y';                ///< the model's up axis: 'x', 'y' or 'z'
  double zoom = 1.0;            ///< > 1: a close-up on `focus` (the box centre by default)
  double margin = 0.06;         ///< free border, as a fraction of the image size

  void check() const;  ///< ConfigError naming the field
};

/// Screen coordinates: x to the right, y downwards (pixel rows), depth growing towards the viewer.
class Camera {
 public:
  /// Fits the box's eight corners into a width x height image.
  Camera(const BoundingBox& box, int width, int height, const ViewOptions& view);

  Eigen::Vector3d project(const Vec3& p) const;  ///< (x, y, depth) in pixels / model units
  const Vec3& towards_viewer() const { return eye_; }
  const Vec3& right() const { return right_; }
  const Vec3& up() const { return up_; }
  /// Pixels per model unit.
  double scale() const { return scale_; }

 private:
  Vec3 centre_, eye_, right_, up_;
  double scale_ = 1.0;
  double cx_ = 0.0, cy_ = 0.0;
};

}  // namespace dtsl::render
