#include "algorithms/evolution/sign_guard.hpp"

#include <algorithm>
#include <cmath>

namespace dtsl {

std::vector<double> sign_floors(const TSplineBasis& basis, double fraction) {
  const Octree& tree = basis.octree();
  std::vector<double> floors(basis.size());
  for (int i = 0; i < basis.size(); ++i) floors[i] = fraction * tree.leaf_side(tree.locate(basis.greville(i)));
  return floors;
}

int guard_signs(const LeastSquaresSystem& system, int surface_rows, const std::vector<double>& floors,
                const std::vector<double>& before, std::vector<double>& after) {
  std::vector<char> at_surface(system.unknowns, 0);
  for (int e = 0; e < system.row_begin[surface_rows]; ++e) at_surface[system.column[e]] = 1;
  int changed = 0;
  for (int k = 0; k < system.unknowns; ++k) {
    if (at_surface[k]) continue;
    const int i = system.control[k];
    const double old = before[i];
    if (old == 0.0) continue;
    const double sign = old > 0.0 ? 1.0 : -1.0;
    const double least = std::min(floors[i], std::abs(old));
    if (sign * after[i] < least) {
      after[i] = sign * least;
      ++changed;
    }
  }
  return changed;
}

int hold_outside(const std::vector<char>& held, const std::vector<double>& floors, const std::vector<double>& before,
                 std::vector<double>& after) {
  int changed = 0;
  for (std::size_t i = 0; i < held.size(); ++i) {
    if (!held[i] || !(before[i] > 0.0)) continue;
    const double least = std::min(floors[i], before[i]);
    if (after[i] < least) {
      after[i] = least;
      ++changed;
    }
  }
  return changed;
}

}  // namespace dtsl
