// Harmonic fill of the displacement field over holes (see hole_fill.hpp).
#include "algorithms/displacement/hole_fill.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "framework/core/connected_components.hpp"
#include "framework/core/error.hpp"

namespace dtsl {

HoleFillReport harmonic_fill(const std::vector<std::vector<int>>& neighbours, const std::vector<char>& known,
                             std::vector<double>& values) {
  HoleFillReport report;
  const int n = static_cast<int>(neighbours.size());
  std::vector<int> index(n, -1);
  int m = 0;
  for (int i = 0; i < n; ++i)
    if (!known[i]) index[i] = m++;
  report.unknown = static_cast<std::size_t>(m);
  if (m == 0) return report;

  // Components of unknowns that touch no known vertex have no boundary condition: they get 0 (the base
  // surface) and are left out of the system so it stays positive definite.
  std::vector<char> unknown(n, 0), reached(n, 0);
  for (int i = 0; i < n; ++i) unknown[i] = !known[i];
  for (const std::vector<int>& group : connected_groups(neighbours, unknown)) {
    bool anchored = false;
    for (std::size_t k = 0; k < group.size() && !anchored; ++k)
      for (int j : neighbours[group[k]]) anchored = anchored || known[j];
    if (anchored)
      for (int i : group) reached[i] = 1;
  }
  m = 0;
  for (int i = 0; i < n; ++i) {
    index[i] = -1;
    if (!known[i]) {
      if (reached[i]) index[i] = m++;
      else values[i] = 0.0, ++report.unreached;
    }
  }
  if (m == 0) return report;

  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(m);
  for (int i = 0; i < n; ++i) {
    if (index[i] < 0) continue;
    triplets.emplace_back(index[i], index[i], static_cast<double>(neighbours[i].size()));
    for (int j : neighbours[i]) {
      if (index[j] >= 0) triplets.emplace_back(index[i], index[j], -1.0);
      else rhs[index[i]] += values[j];  // known (or unreached = 0) neighbour: a boundary value
    }
  }
  Eigen::SparseMatrix<double> L(m, m);
  L.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(L);
  if (solver.info() != Eigen::Success) throw AlgorithmError("displacement hole fill: the Laplace system is singular");
  const Eigen::VectorXd x = solver.solve(rhs);
  for (int i = 0; i < n; ++i)
    if (index[i] >= 0) values[i] = x[index[i]];
  return report;
}

}  // namespace dtsl
