// Spikes (ours): a vertex whose d differs from the mean d of its neighbours by far more than an edge
// (a foot point from another sheet, an extrapolated residual) is refilled from its neighbours with the
// holes. Real corners stay below ~1 edge.
#pragma once

#include <vector>

namespace dtsl {

/// The known vertices (known[v] != 0) whose d[v] differs from the mean d of their known neighbours by
/// more than `limit`, in increasing order.
std::vector<int> find_spikes(const std::vector<std::vector<int>>& neighbours, const std::vector<char>& known,
                             const std::vector<double>& d, double limit);

}  // namespace dtsl
