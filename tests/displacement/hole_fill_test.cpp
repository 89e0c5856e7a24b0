// The harmonic fill on small graphs.
#include <catch2/catch.hpp>

#include "algorithms/displacement/hole_fill.hpp"

using namespace dtsl;

TEST_CASE("harmonic fill interpolates linearly on a path and leaves unreached parts at 0", "[displacement][holes]") {
  // Path 0-1-2-3-4 with ends known; a separate pair 5-6 with no known vertex.
  std::vector<std::vector<int>> nb = {{1}, {0, 2}, {1, 3}, {2, 4}, {3}, {6}, {5}};
  std::vector<char> known = {1, 0, 0, 0, 1, 0, 0};
  std::vector<double> d = {1.0, 9, 9, 9, 3.0, 9, 9};
  const HoleFillReport r = harmonic_fill(nb, known, d);
  CHECK(r.unknown == 5);  // vertices 1, 2, 3, 5 and 6
  CHECK(d[1] == Approx(1.5));
  CHECK(d[2] == Approx(2.0));
  CHECK(d[3] == Approx(2.5));
  CHECK(r.unreached == 2);
  CHECK(d[5] == 0.0);
  CHECK(d[6] == 0.0);
  CHECK(d[0] == 1.0);
  CHECK(d[4] == 3.0);
}
