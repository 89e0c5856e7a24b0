// The registry of hole treatments (ours): the harmonic fill, faired or not.
#include "algorithms/displacement/hole_treatment.hpp"

#include <memory>

#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"

namespace dtsl {

namespace {

// A hole region with more vertices than this keeps the harmonic fill: a bound on fairing's cost, whose
// sparse LU grows faster than the region (Release, 2 cores: 11k vertices 0.5 s, 20k 3 s, 67k 11 s).
// The largest holes met so far: 53k vertices (the 6000-point block, 2.4 s).
constexpr std::size_t kMaxFairedRegionVertices = 100000;

class FairedFill final : public HoleTreatment {
 public:
  explicit FairedFill(int continuity) : continuity_(continuity) {}
  void fair(const TriangleMesh& base, const std::vector<Vec3>& normals, const std::vector<std::vector<int>>& neighbours,
            const std::vector<int>& hole_vertices, std::vector<double>& d, TriangleMesh& displaced,
            HoleTreatmentReport& report) const override {
    if (continuity_ < 0 || hole_vertices.empty()) return;
    Stopwatch timer;
    std::vector<char> free(displaced.vertices.size(), 0);
    for (int v : hole_vertices) free[v] = 1;
    try {
      report.fairing = fair_holes(displaced, free, neighbours, continuity_, kMaxFairedRegionVertices);
      for (int v : hole_vertices) d[v] = (displaced.vertices[v] - base.vertices[v]).dot(normals[v]);
    } catch (const AlgorithmError& e) {
      report.fairing_error = e.what();
    }
    report.fairing_seconds = timer.seconds();
  }

 private:
  int continuity_;  // -1: the harmonic fill alone
};

}  // namespace

nlohmann::json HoleTreatmentReport::summary() const {
  nlohmann::json s = {{"hole_vertices_filled", fill.unknown - fill.unreached},
                      {"hole_vertices_unreached", fill.unreached},
                      {"hole_vertices_faired", fairing.vertices},
                      {"hole_regions_faired", fairing.regions},
                      {"hole_fairing_failures", fairing.failed_regions},
                      {"hole_regions_weakly_anchored", fairing.weakly_anchored_regions},
                      {"hole_regions_too_large", fairing.oversized_regions},
                      {"hole_region_max_vertices", fairing.largest_region},
                      {"hole_fairing_seconds", fairing_seconds}};
  if (!fairing_error.empty()) s["hole_fairing_skipped"] = fairing_error;
  return s;
}

Registry<HoleTreatment>& hole_treatments() {
  static Registry<HoleTreatment> registry("hole treatment");
  static const bool registered = [] {
    registry.add("harmonic", "ours: the harmonic fill of the displacements (the base surface's shape across a hole)",
                 [] { return std::make_unique<FairedFill>(-1); });
    registry.add("membrane", "ours: the harmonic fill, then the hole vertices faired by the Laplacian (Liepa 2003)",
                 [] { return std::make_unique<FairedFill>(0); });
    registry.add("thin_plate",
                 "ours: the harmonic fill, then the hole vertices faired by the bi-Laplacian (the rim's slope "
                 "continues into the hole; Liepa 2003)",
                 [] { return std::make_unique<FairedFill>(1); });
    return true;
  }();
  (void)registered;
  return registry;
}

}  // namespace dtsl
