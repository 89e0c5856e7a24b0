// noise_estimate POINTS [NEIGHBOURS SMALL_NEIGHBOURS [QUANTILE]]: how noisy a point cloud is, as the displacement filter
// sees it (algorithms/displacement/noise_estimate.hpp): the noise's standard deviation along the
// normal and the median spacing, in the file's units. A diagnostic command, not a test.
#include <cstdio>
#include <string>

#include "algorithms/displacement/noise_estimate.hpp"
#include "framework/core/error.hpp"
#include "framework/io/io.hpp"

int main(int argc, char** argv) {
  if (argc < 2 || argc == 3 || argc > 5) {
    std::fprintf(stderr, "usage: noise_estimate POINTS [NEIGHBOURS SMALL_NEIGHBOURS [QUANTILE]]\n");
    return 2;
  }
  try {
    const dtsl::PointCloud cloud = dtsl::read_points(argv[1]);
    dtsl::NoiseEstimateOptions o;
    if (argc > 3) o.neighbours = std::stoi(argv[2]), o.small_neighbours = std::stoi(argv[3]);
    if (argc > 4) o.quantile = std::stod(argv[4]);
    const dtsl::NoiseEstimate e = dtsl::estimate_noise(cloud.points, o);
    std::printf("points %zu  neighbours %d/%d  quantile %.2f  rms %.4e/%.4e  sigma %.4e  spacing %.4e  fitted %d\n",
                cloud.size(), o.small_neighbours, o.neighbours, o.quantile, e.rms_small, e.rms_large, e.sigma,
                e.spacing, e.fitted_points);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "noise_estimate: %s\n", e.what());
    return 1;
  }
  return 0;
}
