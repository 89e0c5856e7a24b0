// Shared T-meshes for the T-spline tests: an adaptive one with T-junctions (from a strongly
// non-uniform sample) per balance kind, and the uniform grid. Built once per test run.
#pragma once

#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "algorithms/tspline/tspline.hpp"
#include "tests/tspline/point_sets.hpp"

namespace dtsl::test {

/// 6000 points on a torus, 30x denser on one side: the adaptive T-mesh reaches level 5 on the dense
/// side and stays at 3 elsewhere, with balance transitions (T-junctions) in between.
inline const std::vector<Vec3>& nonuniform_points() {
  static const std::vector<Vec3> p = nonuniform_torus_points(6000, 0.6, 0.25, 30.0, 7);
  return p;
}

inline std::shared_ptr<const TSplineBasis> adaptive_basis(const std::string& balance = "face") {
  static std::map<std::string, std::shared_ptr<const TSplineBasis>> cache;
  auto& b = cache[balance];
  if (!b) {
    TMeshOptions o;
    o.max_depth = 5;
    o.points_per_cell = 16;
    o.balance = balance;
    b = std::make_shared<TSplineBasis>(build_octree(nonuniform_points(), o));
  }
  return b;
}

/// The uniform tensor-product grid of 16 cells per axis.
inline std::shared_ptr<const TSplineBasis> uniform_basis() {
  static const auto b = std::make_shared<TSplineBasis>(uniform_octree(4, 0.25));
  return b;
}

struct NamedBasis {
  const char* name;
  std::shared_ptr<const TSplineBasis> basis;
};

/// Every T-mesh kind the property tests run on.
inline std::vector<NamedBasis> all_bases() {
  return {{"adaptive (face balance)", adaptive_basis("face")},
          {"adaptive (edge balance)", adaptive_basis("edge")},
          {"adaptive (vertex balance)", adaptive_basis("vertex")},
          {"uniform 16^3", uniform_basis()}};
}

/// Coefficients uniform in [-1, 1]: a generic function, so no property holds by symmetry.
inline std::vector<double> random_coefficients(const TSplineBasis& basis, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> c(basis.size());
  for (double& x : c) x = u(rng);
  return c;
}

/// Points uniform in the box, plus its 8 corners and the centres of its 6 faces.
inline std::vector<Vec3> random_points(const BoundingBox& box, std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> p;
  for (int k = 0; k < 8; ++k)
    p.push_back(Vec3((k & 1) ? box.max.x() : box.min.x(), (k & 2) ? box.max.y() : box.min.y(),
                     (k & 4) ? box.max.z() : box.min.z()));
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      Vec3 c = box.center();
      c[a] = side ? box.max[a] : box.min[a];
      p.push_back(c);
    }
  while (p.size() < n + 14)
    p.push_back(box.min + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(box.max - box.min));
  return p;
}

/// Faces between a leaf and a finer face neighbour: the faces with T-junctions. Returned as
/// (leaf number, axis): the face is the leaf's upper face along `axis`.
inline std::vector<std::pair<int, int>> t_junction_faces(const Octree& tree) {
  std::vector<std::pair<int, int>> faces;
  for (int l = 0; l < tree.leaf_count(); ++l) {
    const Octree::Cell& c = tree.leaf(l);
    const int s = tree.cell_size(c.level);
    for (int a = 0; a < 3; ++a) {
      Int3 probe = c.origin;
      probe[a] += s;
      if (probe[a] >= tree.resolution()) continue;
      if (tree.leaf(tree.leaf_at(probe)).level > c.level) faces.emplace_back(l, a);
    }
  }
  return faces;
}

}  // namespace dtsl::test
