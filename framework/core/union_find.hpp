// Disjoint sets over 0..n-1 (union-find with path halving): the one implementation behind mesh
// components, boundary loops and the fans around a vertex.
#pragma once

#include <cstddef>
#include <numeric>
#include <vector>

namespace dtsl {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), std::size_t{0}); }

  /// The representative of x's set. Pre-condition: x < size().
  std::size_t find(std::size_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  /// Joins the sets of a and b; b's representative stays the representative.
  void unite(std::size_t a, std::size_t b) { parent_[find(a)] = find(b); }
  std::size_t size() const { return parent_.size(); }

 private:
  std::vector<std::size_t> parent_;
};

}  // namespace dtsl
