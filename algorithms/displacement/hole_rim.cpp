#include "algorithms/displacement/hole_rim.hpp"

#include "framework/core/connected_components.hpp"

namespace dtsl {

std::vector<int> grow_hole_rims(const std::vector<std::vector<int>>& neighbours, const std::vector<double>& one_sidedness,
                                double rim_offset, int rings, int min_hole_vertices, std::vector<char>& known) {
  const std::size_t nv = known.size();
  // The holes large enough to seed a rim: connected components of the hole vertices.
  std::vector<char> seed(nv, 0), hole(nv, 0);
  for (std::size_t v = 0; v < nv; ++v) hole[v] = !known[v];
  for (const std::vector<int>& component : connected_groups(neighbours, hole))
    if (static_cast<int>(component.size()) >= min_hole_vertices)
      for (int v : component) seed[v] = 1;
  std::vector<int> joined;
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<int> joining;
    for (std::size_t v = 0; v < nv; ++v) {
      if (!known[v] || one_sidedness[v] <= rim_offset) continue;
      for (int u : neighbours[v])
        if (!known[u] && seed[u]) {
          joining.push_back(static_cast<int>(v));
          break;
        }
    }
    if (joining.empty()) break;
    for (int v : joining) known[v] = 0, seed[v] = 1;
    joined.insert(joined.end(), joining.begin(), joining.end());
  }
  return joined;
}

}  // namespace dtsl
