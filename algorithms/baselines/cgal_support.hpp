// Private to algorithms/baselines: what the CGAL reconstructors share — exception translation and the
// conversion of their index triples into an outward-oriented TriangleMesh. No CGAL header here.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "algorithms/baselines/baseline.hpp"

namespace dtsl::baselines {

/// Runs `body` (a CGAL call) and turns std::bad_alloc, CGAL's failure exceptions and other
/// std::exceptions into AlgorithmError naming `method`.
template <class F>
void guarded_cgal_call(const std::string& method, F&& body) {
  try {
    body();
  } catch (...) {
    rethrow_library_failure(method, "CGAL", "reduce the input size");
  }
}

/// The mesh of `facets` (index triples into `vertices`) after soup_to_mesh's clean-up, turned outward
/// (orient_outward about the vertices' centroid). Records the clean-up counts and whether it flipped
/// in `summary`. Throws AlgorithmError for more vertices than an index can hold.
TriangleMesh interpolating_mesh(const std::vector<Vec3>& vertices, const std::vector<std::array<std::size_t, 3>>& facets,
                                nlohmann::json& summary);

}  // namespace dtsl::baselines
