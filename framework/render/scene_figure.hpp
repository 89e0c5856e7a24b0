// Pictures of point sets, meshes and line sets side by side: one column per item (e.g. input points, points
// + T-mesh, MI, MD, MS),
// one row per view, all items framed by the same box so the stages can be compared pixel for pixel.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "framework/core/types.hpp"
#include "framework/render/camera.hpp"
#include "framework/render/image.hpp"
#include "framework/render/rasterizer.hpp"

namespace dtsl::render {

struct SceneItem {
  std::string label;                    ///< drawn above the column
  const TriangleMesh* mesh = nullptr;   ///< a mesh, and/or
  const std::vector<Vec3>* points = nullptr;  ///< a point set, and/or
  const std::vector<std::array<Vec3, 2>>* lines = nullptr;  ///< line segments (e.g. the T-mesh's cell edges)
  /// Drawn into the depth buffer only: hides the points and lines behind this surface (not those on it),
  /// so a wireframe around a surface shows its front half only. Not part of scene_box().
  const TriangleMesh* occluder = nullptr;
};

struct SceneOptions {
  int panel_size = 400;                 ///< pixels per (square) view
  int supersample = 2;                  ///< rendered at this factor and box-filtered (anti-aliasing)
  std::vector<ViewOptions> views = {ViewOptions{}, ViewOptions{210.0, 20.0}};
  ShadingOptions shading;
  /// Width in output pixels (multiplied by supersample). Half-transparent warm lines: cells read as a
  /// light grid the (blue, opaque) points stand out against.
  LineStyle lines{{215, 95, 35}, 1.0, 0.55};
  double occluder_offset = 0.01; ///< an occluder is pushed this fraction of the box diagonal away from the viewer

  void check() const;  ///< ConfigError naming the field
};

/// The box around every vertex and point of `items` (invalid if all are empty). Lines do not count: they
/// are context (cells around a surface reach beyond it) and may be clipped at the panel's border.
BoundingBox scene_box(const std::vector<SceneItem>& items);

/// One view of one item, `panel_size` square, without label.
Image render_view(const SceneItem& item, const BoundingBox& box, const ViewOptions& view, const SceneOptions& options);

/// The grid: items as columns with their labels on top, views as rows.
Image render_scene(const std::vector<SceneItem>& items, const SceneOptions& options);

}  // namespace dtsl::render
