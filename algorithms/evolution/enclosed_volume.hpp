// Whether an initial level set from the data (data_carving.hpp, data_wrap.hpp) has found a volume that
// the data enclose. A carving or wrap ball passes an open sheet of data on both sides when the sheet has
// a hole wider than the ball — a plane cut, a scan that misses one side — and the inside it leaves is a
// shell no thicker than the wrap's offset around the data: the evolution then pulls both faces of the
// shell onto the data and tears it into hundreds of bubbles. Where the data bound a solid, the inside
// reaches deeper than the wrap's offset within a few spacings of the data points; a data point near which
// the inside is nowhere that deep is unenclosed.
#pragma once

#include <functional>
#include <vector>

#include "algorithms/evolution/data_wrap.hpp"
#include "framework/core/types.hpp"

namespace dtsl {

/// The depth, in median spacings, that the inside must reach near an enclosed data point: 1.5 x the wrap's
/// offset (data_wrap.hpp), which is all the depth the shell around an open sheet has.
constexpr double kEnclosedDepthSpacings = 1.5 * kWrapOffsetSpacings;

/// Above this fraction of unenclosed data points, the data do not bound a volume at the ball's scale and
/// the evolution starts from the enclosing sphere instead (paper §2.1), which bridges missing data. On the
/// topology suite's dev half every input stays below 0.5 % and the test half's plane-cut block is at 64 %
/// (thin parts of solids: a coarse dinosaur's limbs 5 %).
constexpr double kMaxUnenclosedFraction = 0.1;

struct EnclosureCheck {
  int tested = 0, unenclosed = 0;
  double fraction() const { return tested ? double(unenclosed) / double(tested) : 0.0; }
};

/// Tests up to max_tested data points (evenly strided): a point p with spacing s = max(its local spacing,
/// `median_spacing`) is enclosed when signed_distance (negative inside) is at most -kEnclosedDepthSpacings x
/// median_spacing at some probe p + t u, t in {0.75, 1.5, 3} x s, u one of the 26 directions to the unit
/// cube's faces, edges and corners.
EnclosureCheck check_enclosure(const std::vector<Vec3>& points, const std::vector<double>& local_spacing,
                               double median_spacing, const std::function<double(const Vec3&)>& signed_distance,
                               int max_tested = 2000);

}  // namespace dtsl
