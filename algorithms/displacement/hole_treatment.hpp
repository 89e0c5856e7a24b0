// What fills a hole (ours; the paper's Gaussian filter leaves vertices without data undefined) as
// plugins. Every treatment starts from the harmonic fill of the displacements (hole_fill.hpp: the
// base surface's shape continued across the hole); the fairing ones then move the hole vertices'
// positions to minimise a Laplacian energy with the data-supported vertices fixed (hole_fairing.hpp):
//   harmonic    the harmonic fill alone;
//   membrane    then the Laplacian (continuity 0);
//   thin_plate  then the bi-Laplacian (continuity 1: the rim's slope continues into the hole; default).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "algorithms/displacement/hole_fairing.hpp"
#include "algorithms/displacement/hole_fill.hpp"
#include "framework/config/options.hpp"
#include "framework/core/types.hpp"
#include "framework/registry/registry.hpp"

namespace dtsl {

struct HoleTreatmentReport {
  HoleFillReport fill;
  HoleFairingReport fairing;
  double fairing_seconds = 0.0;
  std::string fairing_error;  ///< a base mesh CGAL cannot take: the harmonic fill stays
  nlohmann::json summary() const;
};

class HoleTreatment {
 public:
  virtual ~HoleTreatment() = default;
  Options& options() { return options_; }
  /// Moves the hole vertices of `displaced` (which is `base` displaced by d along `normals`), with the
  /// others fixed; d becomes the normal part of each moved vertex's move. Never throws for a mesh the
  /// fairing cannot take: it says so in the report and leaves the vertices.
  virtual void fair(const TriangleMesh& base, const std::vector<Vec3>& normals,
                    const std::vector<std::vector<int>>& neighbours, const std::vector<int>& hole_vertices,
                    std::vector<double>& d, TriangleMesh& displaced, HoleTreatmentReport& report) const = 0;

 private:
  NoOptions options_;
};

Registry<HoleTreatment>& hole_treatments();

}  // namespace dtsl
