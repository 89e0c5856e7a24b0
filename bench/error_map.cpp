// error_map POINTS MESH [TOP]: where a mesh is far from its data. Prints the distribution of the
// point-to-mesh distances (the paper's Eq. 9 errors) and the TOP worst points with their closest mesh
// point, to find the regions a stage misses. A diagnostic command, not a test.
#include <algorithm>
#include <cstdio>
#include <numeric>
#include <string>

#include "framework/core/error.hpp"
#include "framework/io/io.hpp"
#include "framework/metrics/metrics.hpp"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: error_map POINTS MESH [TOP]\n");
    return 2;
  }
  try {
    const dtsl::PointCloud cloud = dtsl::read_points(argv[1]);
    const dtsl::TriangleMesh mesh = dtsl::read_mesh(argv[2]);
    const int top = argc > 3 ? std::stoi(argv[3]) : 20;
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
  }
}
