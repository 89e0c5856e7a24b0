#include "framework/report/report_options.hpp"

#include "framework/core/error.hpp"

namespace dtsl::report {

void ReportOptions::check() const {
  if (views < 1 || views > 4) throw ConfigError("--views: must be in [1, 4]");
  if (panel_size < 64 || panel_size > 2048) throw ConfigError("--size: must be in [64, 2048] pixels");
  if (up != 'x' && up != 'y' && up != 'z') throw ConfigError("--up: must be x, y or z");
  if (!(closeup >= 1.0 && closeup <= 20.0)) throw ConfigError("--closeup: must be in [1, 20] (1 = none)");
}

render::SceneOptions ReportOptions::scene() const {
  check();
  render::SceneOptions s;
  s.panel_size = panel_size;
  s.views.clear();
  const double azimuths[] = {30.0, 210.0, 120.0, 300.0};
  for (int i = 0; i < views; ++i) {
    render::ViewOptions v;
    v.azimuth_deg = azimuths[i];
    v.up = up;
    s.views.push_back(v);
  }
  if (closeup > 1.0) {
    render::ViewOptions v = s.views.front();
    v.zoom = closeup;
    s.views.push_back(v);
  }
  return s;
}

}  // namespace dtsl::report
