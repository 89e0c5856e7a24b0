// JSON form of the metric results, as written into every run's metrics file. An undefined value (NaN,
// e.g. the genus of an open mesh) is written as null, never as a number a table could mistake for data.
#include <cmath>

#include "framework/metrics/metrics.hpp"

namespace dtsl {

namespace {
nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }
}  // namespace

nlohmann::json to_json(const PointErrors& e) {
  return {{"e_avr", number(e.e_avr)}, {"e_max", number(e.e_max)}};
}

nlohmann::json to_json(const SurfaceMetrics& m) {
  return {{"accuracy", number(m.accuracy)},
          {"completeness", number(m.completeness)},
          {"chamfer", number(m.chamfer)},
          {"hausdorff", number(m.hausdorff)},
          {"normal_consistency", number(m.normal_consistency)},
          {"precision", number(m.precision)},
          {"recall", number(m.recall)},
          {"fscore", number(m.fscore)},
          {"tau", number(m.tau)}};
}

nlohmann::json to_json(const MeshStats& s) {
  return {{"vertices", s.vertices},
          {"faces", s.faces},
          {"boundary_edges", s.boundary_edges},
          {"nonmanifold_edges", s.nonmanifold_edges},
          {"nonmanifold_vertices", s.nonmanifold_vertices},
          {"watertight", s.watertight},
          {"components", s.components},
          {"euler_characteristic", s.euler_characteristic},
          {"genus", number(s.genus)},
          {"min_angle_deg", number(s.min_angle_deg)},
          {"min_angle_p01_deg", number(s.min_angle_p01_deg)},
          {"min_angle_mean_deg", number(s.min_angle_mean_deg)},
          {"valence6_fraction", number(s.valence6_fraction)},
          {"degenerate_faces", s.degenerate_faces}};
}

}  // namespace dtsl
