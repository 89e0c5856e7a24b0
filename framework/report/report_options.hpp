// Options of `dtsl report`: how the meshes are pictured and which figures are made.
#pragma once

#include "framework/render/scene_figure.hpp"

namespace dtsl::report {

struct ReportOptions {
  bool renders = true;     ///< pictures of points and meshes (the slow part); charts are always made
  int views = 2;           ///< views per mesh, in [1, 4]: azimuth 30, 210, 120, 300 degrees
  int panel_size = 360;    ///< pixels per view
  char up = 'y';           ///< the models' up axis (CGAL's models: y)
  double closeup = 1.0;    ///< > 1: one more row, a close-up by this factor on the box centre
  bool progress = true;    ///< a line per run on stderr

  void check() const;                   ///< ConfigError naming the option
  render::SceneOptions scene() const;   ///< the rasteriser's options these imply
};

}  // namespace dtsl::report
