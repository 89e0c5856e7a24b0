// A small software rasteriser for figures: triangles with a z-buffer and flat Lambert shading under
// a fixed light (front faces in the mesh colour, back faces — seen through holes — in a warm tint),
// points as depth-tested round splats, and line segments depth-tested against what is drawn (hidden or
// faded behind it). Headless: no display, no OpenGL.
#pragma once

#include <array>
#include <vector>

#include "framework/core/types.hpp"
#include "framework/render/camera.hpp"
#include "framework/render/image.hpp"

namespace dtsl::render {

struct ShadingOptions {
  Rgb front{178, 196, 222};  ///< mesh colour of faces turned to the viewer
  Rgb back{222, 160, 120};   ///< faces turned away (the inside, through a hole)
  double ambient = 0.22;     ///< light that reaches every face, in [0, 1]
  Rgb point_near{20, 40, 110}, point_far{140, 170, 230};  ///< splats are coloured by depth
  double point_radius = 1.5;  ///< pixels
};

/// How line segments are drawn. Lines are tested against the depth buffer but do not write it: they
/// never hide points or one another, and a line crossing a surface is drawn up to the crossing.
struct LineStyle {
  Rgb colour{200, 80, 30};
  double width = 1.0;         ///< pixels across the line's minor axis (at least 1)
  double alpha = 1.0;         ///< opacity where the line is in front
  double hidden_alpha = 0.0;  ///< opacity where something drawn is in front of it (0: hidden)
  /// Depth (model units) added towards the viewer before the test, so that a line lying on a surface
  /// is not hidden by the surface's own triangles.
  double depth_bias = 0.0;
};

/// A colour image with its depth buffer, so meshes and points can be drawn into the same picture.
class Canvas {
 public:
  Canvas(int width, int height, Rgb background = {255, 255, 255});
  Image& image() { return image_; }
  const Image& image() const { return image_; }

  void draw_mesh(const TriangleMesh& mesh, const Camera& camera, const ShadingOptions& shading = {});
  void draw_points(const std::vector<Vec3>& points, const Camera& camera, const ShadingOptions& shading = {});
  /// Each segment as a line of pixels: one pixel per step along its longer screen axis, end points
  /// included, so the pixels between the ends are covered without gaps and none twice (alpha blends
  /// once per segment).
  void draw_lines(const std::vector<std::array<Vec3, 2>>& segments, const Camera& camera, const LineStyle& style = {});
  /// Writes the mesh's depth only (nothing visible), `offset` model units away from the viewer: an
  /// occluder that hides what lies behind the surface but not what lies on it (points, lines).
  void draw_depth(const TriangleMesh& mesh, const Camera& camera, double offset = 0.0);

 private:
  bool test_and_set(int x, int y, double depth);
  Image image_;
  std::vector<double> depth_;
};

}  // namespace dtsl::render
