// The data's carving: an initial level set whose topology the data decide, with a carving ball that
// grows and shrinks with the local sampling spacing (ours; compare data_wrap.hpp, whose ball has one
// radius for the whole cloud and so slips into the solid wherever the sampling is sparser than the
// median, e.g. along a density ramp).
//
// The space is split by the Delaunay tetrahedrisation of the data points. Starting from the infinite
// cells, a ball floods from cell to cell through a facet when the largest empty ball that can pass the
// facet (its circumscribed ball if that is empty — a Gabriel facet — otherwise the smaller of the two
// cells' circumscribed balls) has a radius of at least alpha x the largest local spacing of the facet's
// three points: the alpha-shape's gate test (Edelsbrunner and Mucke, "Three-dimensional alpha shapes",
// ACM TOG 1994) with a radius per facet instead of one alpha. Cells the flood does not reach are inside.
// The signed distance is the distance to the facets between flooded and unflooded cells, negative in
// unflooded cells; in flooded cells it is the smaller of that and the distance to the nearest data point
// (data the flood passed on both sides, an open sheet or a sparse strand, are then a zero of it too). The
// boundary passes through data points, and initial_level_set.hpp lowers the level set until the data lie
// inside.
//
// Separate objects (ours): where two pieces of the data (data_pieces.hpp: the components of the
// k-nearest-neighbour graph) face each other across a gap narrower than the ball, the flood above stops
// short and the gap stays inside, joining the objects. A second flood therefore goes on from the flooded
// cells through every facet whose three corners do not all lie on one piece, however small: such a facet
// spans a gap between pieces, never the sampling of one surface. No gate, no knob, and no change for
// data in one piece. (The paper, §2.1, leaves the split of nearby objects to the evolution from an
// enclosing sphere, which keeps a neck where the speed fades between them: docs/experiments.md.)
//
// `initial: carve` (evolution.cpp) uses the union of this carving's inside and the alpha wrap's
// (data_wrap.hpp, same alpha) of each piece on its own: the min of the carving's signed distance and
// that of the wrap of the piece nearest to x. Each fails by making the inside too small, in different
// places: the carving floods a tube thinner than its ball (the suite's thin ring), the wrap's one ball
// slips into sparse parts (its 50x density ramp came out genus 140: wrap_x); the union keeps both (dev
// half of the topology suite: results/suite_dev/carve_x against wrap_x). One wrap of all the data would
// join the pieces again across the gap the second flood opened.
#pragma once

#include <memory>
#include <vector>

#include "framework/core/types.hpp"

namespace dtsl {

struct CarvingSummary {
  double spacing = 0.0;    ///< the data's median local spacing (frame units), for the record
  double alpha = 0.0;      ///< the ball's radius in local spacings
  int inside_cells = 0, boundary_facets = 0;
  int data_pieces = 0;     ///< connected pieces of the data (data_pieces.hpp)
  int reopened_cells = 0;  ///< cells the second flood reached
  double seconds = 0.0;
};

struct CarvingValue {
  double distance = 0.0;  ///< signed distance to the carved boundary (negative inside)
  int piece = 0;          ///< the piece (pieces()) of the data point nearest to x
};

class DataCarving {
 public:
  /// Carves the space around `points` with a ball of alpha_spacings x the local spacing (the mean distance
  /// to the kSpacingNeighbours nearest points, support.hpp). AlgorithmError for fewer than 4 points,
  /// non-finite coordinates, all points coinciding or coplanar, or a non-positive alpha.
  DataCarving(const std::vector<Vec3>& points, double alpha_spacings);
  ~DataCarving();
  DataCarving(const DataCarving&) = delete;
  DataCarving& operator=(const DataCarving&) = delete;

  /// Signed distance from x to the carved boundary (negative inside; thread-safe).
  double operator()(const Vec3& x) const;
  /// That distance and the piece of the data point nearest to x (thread-safe).
  CarvingValue evaluate(const Vec3& x) const;
  /// Whether x lies in a cell the second flood opened, a gap between pieces (thread-safe).
  bool reopened(const Vec3& x) const;
  const CarvingSummary& summary() const;
  /// Each data point's local spacing, in input order (the ball's radius there is alpha x it).
  const std::vector<double>& local_spacing() const;
  /// Each data point's piece (data_pieces.hpp), in input order: 0 .. summary().data_pieces - 1.
  const std::vector<int>& pieces() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dtsl
