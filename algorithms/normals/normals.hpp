// Oriented normals for methods that need them (the PCL baselines). PCL's viewpoint flip is not a global
// orientation; CGAL's jet fitting followed by minimum-spanning-tree propagation is.
#pragma once

#include <string>
#include <vector>

#include "framework/config/options.hpp"
#include "framework/core/types.hpp"

namespace dtsl {

/// Where a baseline's normals come from. Reported in every result as "normals_source".
struct NormalSourceOptions final : Options {
  std::string normals = "auto";  ///< ground_truth | jet_mst | pca_mst | auto (ground truth if present, else jet_mst)
  int normal_neighbours = 18;    ///< k of the k-nearest-neighbour fits and the orientation graph

  void visit(FieldVisitor& v) override;
  void check() const override;
};

/// Unit normals by jet fitting (or PCA) over k neighbours, oriented consistently by MST propagation and
/// pointing outward (the point of largest z gets +z, as CGAL does). A part the k-neighbour graph does
/// not reach is oriented from its point nearest to the oriented ones if it continues their surface,
/// else (a separate object) from its own highest point. Exact duplicate points share one normal. Points
/// whose orientation could not be propagated keep an unoriented normal; their count is returned in
/// `unoriented` if given. Throws AlgorithmError for k < 3, fewer than max(3, k+1) distinct points, a
/// non-finite point, or a neighbourhood too degenerate to fit.
std::vector<Vec3> estimate_oriented_normals(const std::vector<Vec3>& points, int k, bool use_jet,
                                            std::size_t* unoriented = nullptr);

/// `cloud` with normals from the configured source; `source_used` receives the name actually used
/// ("ground_truth", "jet_mst" or "pca_mst"). Throws AlgorithmError if ground_truth is required but absent.
PointCloud with_normals(const PointCloud& cloud, const NormalSourceOptions& options, std::string& source_used);

}  // namespace dtsl
