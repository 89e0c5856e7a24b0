// A small software rasteriser for figures: triangles with a z-buffer and flat Lambert shading under
// a fixed light (front faces in the mesh colour, back faces — seen through holes — in a warm tint),
// and points as depth-tested round splats. Headless: no display, no OpenGL.
#pragma once

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

/// A colour image with its depth buffer, so meshes and points can be drawn into the same picture.
class Canvas {
 public:
  Canvas(int width, int height, Rgb background = {255, 255, 255});
  Image& image() { return image_; }
  const Image& image() const { return image_; }

  void draw_mesh(const TriangleMesh& mesh, const Camera& camera, const ShadingOptions& shading = {});
  void draw_points(const std::vector<Vec3>& points, const Camera& camera, const ShadingOptions& shading = {});

 private:
  bool test_and_set(int x, int y, double depth);
  Image image_;
  std::vector<double> depth_;
};

}  // namespace dtsl::render
