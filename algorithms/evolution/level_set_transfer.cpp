#include "algorithms/evolution/level_set_transfer.hpp"

#include <map>
#include <memory>
#include <utility>

#include "framework/core/timer.hpp"

namespace dtsl {

Balance balance_of(const Octree& tree) {
  if (is_balanced(tree, Balance::vertex)) return Balance::vertex;
  if (is_balanced(tree, Balance::edge)) return Balance::edge;
  return Balance::face;
}

nlohmann::json to_json(const TransferReport& r) {
  return {{"changed", r.changed}, {"seconds", r.seconds}};
}

TSpline transfer_level_set(const TSpline& old, Octree refined, TransferReport* report) {
  Stopwatch clock;
  auto basis = std::make_shared<TSplineBasis>(std::move(refined));
  const TSplineBasis& previous = old.basis();
  std::map<Int3, int> old_index;
  for (int i = 0; i < previous.size(); ++i) old_index.emplace(previous.vertex(i), i);
  std::vector<double> c(basis->size());
  std::vector<char> changed(basis->size(), 0);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < basis->size(); ++i) {
    const auto it = old_index.find(basis->vertex(i));
    if (it != old_index.end() && previous.knots(it->second) == basis->knots(i)) {
      c[i] = old.coefficients()[it->second];
    } else {
      c[i] = old.evaluate(basis->greville(i));
      changed[i] = 1;
    }
  }
  TSpline f(std::move(basis), std::move(c));
  TransferReport record;
  for (char k : changed) record.changed += k;
  record.changed_flags = std::move(changed);
  record.seconds = clock.seconds();
  if (report) *report = record;
  return f;
}

}  // namespace dtsl
