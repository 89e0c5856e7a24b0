// Pictures of point sets and meshes side by side: one column per item (e.g. input points, MI, MD, MS),
// one row per view, all items framed by the same box so the stages can be compared pixel for pixel.
#pragma once

#include <string>
#include <vector>

#include "framework/core/types.hpp"
#include "framework/render/camera.hpp"
#include "framework/render/image.hpp"
#include "framework/render/rasterizer.hpp"

namespace dtsl::render {

struct SceneItem {
  std::string label;                    ///< drawn above the column
  const TriangleMesh* mesh = nullptr;   ///< a mesh, or
  const std::vector<Vec3>* points = nullptr;  ///< a point set (either may be set; both are drawn)
};

struct SceneOptions {
  int panel_size = 400;                 ///< pixels per (square) view
  int supersample = 2;                  ///< rendered at this factor and box-filtered (anti-aliasing)
  std::vector<ViewOptions> views = {ViewOptions{}, ViewOptions{210.0, 20.0}};
  ShadingOptions shading;

  void check() const;  ///< ConfigError naming the field
};

/// The box around every vertex and point of `items` (invalid if all are empty).
BoundingBox scene_box(const std::vector<SceneItem>& items);

/// One view of one item, `panel_size` square, without label.
Image render_view(const SceneItem& item, const BoundingBox& box, const ViewOptions& view, const SceneOptions& options);

/// The grid: items as columns with their labels on top, views as rows.
Image render_scene(const std::vector<SceneItem>& items, const SceneOptions& options);

}  // namespace dtsl::render
