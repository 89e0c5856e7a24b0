// The data's wrap: an initial level set whose topology the data decide before the evolution starts
// (ours; the paper, §2.1, starts from an enclosing sphere and leaves every topology change to the
// evolution). A sphere shrinking onto the data has to open every through-hole and split every pair of
// nearby objects by itself, and where the speed fades near data on both sides (a hole's rim, a gap
// between objects) it keeps a membrane or a neck (docs/experiments.md, the topology suite). The wrap
// instead carves the space outside the data with a ball of radius alpha, which passes through every
// hole and gap wider than about 2 alpha and through no opening of the sampling narrower than alpha;
// what it cannot reach is inside. CGAL's 3D alpha wrapping does the carving (Portaneri et al.,
// "Alpha wrapping with an offset", SIGGRAPH 2022): its output is a watertight, orientable, 2-manifold
// mesh at distance `offset` outside the points, with no self-intersections.
//
// alpha is a multiple of the data's sampling spacing (the median over the points of the mean distance
// to their kSpacingNeighbours nearest neighbours, support.hpp): scale-free, and a ball a few spacings
// wide cannot slip between the samples of a surface into the solid behind it.
#pragma once

#include <memory>
#include <vector>

#include "framework/core/types.hpp"

namespace dtsl {

/// The wrap's offset from the data, in spacings: enough for the quasi-interpolant of its distance to keep
/// the data inside (initial_level_set.hpp lowers it where not), little enough not to narrow the gaps.
constexpr double kWrapOffsetSpacings = 0.5;

struct WrapSummary {
  double spacing = 0.0;  ///< the data's median local spacing (frame units)
  double alpha = 0.0, offset = 0.0;
  int vertices = 0, faces = 0, components = 0, genus = 0;
  double seconds = 0.0;
};

/// The signed distance to the wrap of a point set: negative inside. Thread-safe queries.
class DataWrap {
 public:
  /// Wraps `points` with a ball of radius alpha_spacings x the median local spacing, at offset
  /// offset_spacings x that spacing. AlgorithmError for fewer than 4 points, non-finite coordinates,
  /// non-positive factors, or a wrap that is empty.
  DataWrap(const std::vector<Vec3>& points, double alpha_spacings, double offset_spacings);
  ~DataWrap();
  DataWrap(const DataWrap&) = delete;
  DataWrap& operator=(const DataWrap&) = delete;

  /// Signed Euclidean distance from x to the wrap (negative inside).
  double operator()(const Vec3& x) const;
  const WrapSummary& summary() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dtsl
