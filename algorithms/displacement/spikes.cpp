#include "algorithms/displacement/spikes.hpp"

#include <cmath>

namespace dtsl {

std::vector<int> find_spikes(const std::vector<std::vector<int>>& neighbours, const std::vector<char>& known,
                             const std::vector<double>& d, double limit) {
  std::vector<int> spikes;
  for (std::size_t v = 0; v < known.size(); ++v) {
    if (!known[v]) continue;
    double sum = 0.0;
    int count = 0;
    for (int u : neighbours[v])
      if (known[u]) sum += d[u], ++count;
    if (count > 0 && std::abs(d[v] - sum / count) > limit) spikes.push_back(static_cast<int>(v));
  }
  return spikes;
}

}  // namespace dtsl
