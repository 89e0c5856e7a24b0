#include "framework/render/scene_figure.hpp"

#include <algorithm>
#include <cmath>

#include "framework/core/error.hpp"
#include "framework/render/font.hpp"

namespace dtsl::render {

void SceneOptions::check() const {
  if (panel_size < 32 || panel_size > 4096) throw ConfigError("panel_size: must be in [32, 4096] pixels");
  if (supersample < 1 || supersample > 4) throw ConfigError("supersample: must be in [1, 4]");
  if (views.empty() || views.size() > 8) throw ConfigError("views: between 1 and 8 views");
  for (const ViewOptions& v : views) v.check();
  if (!(lines.width >= 0.5 && lines.width <= 16)) throw ConfigError("lines.width: must be in [0.5, 16] pixels");
  if (!(lines.alpha >= 0 && lines.alpha <= 1) || !(lines.hidden_alpha >= 0 && lines.hidden_alpha <= 1))
    throw ConfigError("lines.alpha, lines.hidden_alpha: must be in [0, 1]");
  if (!(occluder_offset >= 0 && occluder_offset < 0.5)) throw ConfigError("occluder_offset: must be in [0, 0.5)");
}

BoundingBox scene_box(const std::vector<SceneItem>& items) {
  BoundingBox box;
  for (const SceneItem& it : items) {
    if (it.mesh)
      for (const Vec3& v : it.mesh->vertices) box.extend(v);
    if (it.points)
      for (const Vec3& p : *it.points) box.extend(p);
  }
  return box;
}

Image render_view(const SceneItem& item, const BoundingBox& box, const ViewOptions& view, const SceneOptions& o) {
  const int n = o.panel_size * o.supersample;
  Canvas canvas(n, n);
  const Camera camera(box, n, n, view);
  ShadingOptions shading = o.shading;
  if (item.points && !item.points->empty())  // dense sets in smaller splats, so that holes stay visible
    shading.point_radius = std::clamp(0.3 * o.panel_size / std::sqrt(static_cast<double>(item.points->size())), 0.6,
                                      shading.point_radius);
  shading.point_radius *= o.supersample;
  if (item.occluder && box.valid()) canvas.draw_depth(*item.occluder, camera, o.occluder_offset * box.diagonal());
  if (item.mesh) canvas.draw_mesh(*item.mesh, camera, shading);
  if (item.lines) {  // before the points, which lines do not hide (they write no depth)
    LineStyle style = o.lines;
    style.width *= o.supersample;
    canvas.draw_lines(*item.lines, camera, style);
  }
  if (item.points) canvas.draw_points(*item.points, camera, shading);
  return canvas.image().downsample(o.supersample);
}

Image render_scene(const std::vector<SceneItem>& items, const SceneOptions& o) {
  o.check();
  const BoundingBox box = scene_box(items);
  const int label_h = char_height(2) + 12;
  const int cols = static_cast<int>(items.size()), rows = static_cast<int>(o.views.size());
  Image out(std::max(cols, 1) * o.panel_size, label_h + rows * o.panel_size);
  for (int c = 0; c < cols; ++c) {
    std::string label = items[c].label;
    int scale = text_width(label, 2) <= o.panel_size - 8 ? 2 : 1;  // a long label in the small font
    const int fits = std::max(1, (o.panel_size - 8) / char_width(scale));
    if (static_cast<int>(label.size()) > fits) label = label.substr(0, fits);
    draw_text(out, c * o.panel_size + (o.panel_size - text_width(label, scale)) / 2, 6 + (2 - scale) * 4, label,
              {30, 30, 30}, scale);
    for (int r = 0; r < rows; ++r)
      out.paste(render_view(items[c], box, o.views[r], o), c * o.panel_size, label_h + r * o.panel_size);
    if (c > 0)
      for (int y = label_h; y < out.height(); ++y) out.set(c * o.panel_size, y, {210, 210, 210});
  }
  return out;
}

}  // namespace dtsl::render
