#include "algorithms/method/tmesh_lines.hpp"

#include "algorithms/tspline/tspline_io.hpp"

namespace dtsl {

std::vector<std::array<Vec3, 2>> tmesh_edges_around(const Octree& octree, const std::vector<Vec3>& samples) {
  std::vector<char> held(octree.leaf_count(), 0);
  for (const Vec3& p : samples) held[octree.locate(p)] = 1;
  // An edge lies on the boundary of the (up to four) leaves around it: probe them a quarter of a
  // finest cell off the edge's midpoint, across the edge's two normal axes. Lattice lines are a whole
  // finest cell apart, so each probe is strictly inside one leaf.
  const double off = 0.25 * octree.unit();
  std::vector<std::array<Vec3, 2>> kept;
  for (const std::array<Vec3, 2>& e : tmesh_edges(octree)) {
    const Vec3 mid = 0.5 * (e[0] + e[1]);
    int axis = 0;
    (e[1] - e[0]).cwiseAbs().maxCoeff(&axis);
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    bool keep = false;
    for (int k = 0; k < 4 && !keep; ++k) {
      Vec3 probe = mid;
      probe[u] += (k & 1) ? off : -off;
      probe[w] += (k & 2) ? off : -off;
      keep = held[octree.locate(probe)];
    }
    if (keep) kept.push_back(e);
  }
  return kept;
}

}  // namespace dtsl
