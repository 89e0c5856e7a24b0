// error_map POINTS MESH [TOP] [--keep-below x|y|z VALUE]: where a mesh is far from its data. Prints the
// distribution of the point-to-mesh distances (the paper's Eq. 9 errors) and the TOP worst points with
// their closest mesh point, to find the regions a stage misses. --keep-below measures only the points
// whose coordinate on that axis is at most VALUE (e.g. a result's vertices on the side of a plane cut
// where the data are, against the truth). A diagnostic command, not a test.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

#include "framework/core/error.hpp"
#include "framework/io/io.hpp"
#include "framework/metrics/metrics.hpp"

int main(int argc, char** argv) {
  const char* usage = "usage: error_map POINTS MESH [TOP] [--keep-below x|y|z VALUE]\n";
  std::vector<std::string> positional;
  int axis = -1;
  double below = 0.0;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--keep-below") {
      const std::string name = a + 1 < argc ? argv[a + 1] : "";
      if (a + 2 >= argc || name.size() != 1 || name.find_first_of("xyz") != 0) {
        std::fprintf(stderr, "error_map: --keep-below needs an axis x, y or z and a value\n%s", usage);
        return 2;
      }
      axis = name[0] - 'x';
      char* end = nullptr;
      below = std::strtod(argv[a + 2], &end);
      if (end == argv[a + 2] || *end != '\0' || !std::isfinite(below)) {
        std::fprintf(stderr, "error_map: --keep-below %s: '%s' is not a number\n", name.c_str(), argv[a + 2]);
        return 2;
      }
      a += 2;
    } else {
      positional.push_back(arg);
    }
  }
  if (positional.size() < 2 || positional.size() > 3) {
    std::fprintf(stderr, "%s", usage);
    return 2;
  }
  try {
    dtsl::PointCloud cloud = dtsl::read_points(positional[0]);
    const dtsl::TriangleMesh mesh = dtsl::read_mesh(positional[1]);
    int top = 20;
    if (positional.size() > 2) {
      const std::string& t = positional[2];
      if (t.empty() || t.find_first_not_of("0123456789") != std::string::npos || t.size() > 9)
        throw dtsl::Error("TOP must be a whole number of points to list, got '" + t + "'");
      top = std::stoi(t);
    }
    if (axis >= 0) {
      std::vector<dtsl::Vec3> kept;
      for (const auto& p : cloud.points)
        if (p[axis] <= below) kept.push_back(p);
      cloud.points = std::move(kept);
      cloud.normals.clear();
    }
    if (cloud.points.empty()) throw dtsl::Error("no points to measure in " + positional[0]);
    const dtsl::MeshDistance distance(mesh);
    const auto hits = distance.closest_all(cloud.points);
    std::vector<int> order(hits.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return hits[a].distance > hits[b].distance; });
    double sum = 0.0;
    for (const auto& h : hits) sum += h.distance;
    std::printf("points %zu  e_avr %.3e  e_max %.3e\n", hits.size(), sum / hits.size(), hits[order[0]].distance);
    for (double q : {0.5, 0.9, 0.99, 0.999}) {
      const int k = std::min<int>(int(hits.size()) - 1, int((1.0 - q) * hits.size()));
      std::printf("  quantile %.3f: %.3e\n", q, hits[order[k]].distance);
    }
    for (double t : {1e-3, 5e-3, 1e-2, 2e-2, 5e-2}) {
      const auto n = std::count_if(hits.begin(), hits.end(), [&](const auto& h) { return h.distance > t; });
      std::printf("  > %.0e: %ld points, sum of their distance / total %.2f\n", t, long(n),
                  std::accumulate(hits.begin(), hits.end(), 0.0,
                                  [&](double s, const auto& h) { return h.distance > t ? s + h.distance : s; }) / sum);
    }
    for (int i = 0; i < std::min<int>(top, int(order.size())); ++i) {
      const auto& p = cloud.points[order[i]];
      const auto& h = hits[order[i]];
      std::printf("  %.4f at (%.3f %.3f %.3f) -> (%.3f %.3f %.3f)\n", h.distance, p.x(), p.y(), p.z(), h.point.x(),
                  h.point.y(), h.point.z());
    }
  } catch (const dtsl::Error& e) {
    std::fprintf(stderr, "error_map: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error_map: %s\n", e.what());
    return 1;
  }
}
