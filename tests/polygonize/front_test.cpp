// The front bookkeeping of the marching method: replace, split and merge keep every front a
// consistent cycle with the expected points in the expected order.
#include <catch2/catch.hpp>

#include <vector>

#include "algorithms/polygonize/front.hpp"

using namespace dtsl;

namespace {

/// The vertices of front f in order starting at the node holding `first`, after checking that the
/// prev/next links agree and every node knows its front.
std::vector<int> cycle(const FrontSet& s, int f, int first) {
  const std::vector<int> nodes = s.nodes_of(f);
  REQUIRE(static_cast<int>(nodes.size()) == s.front_size(f));
  int start = -1;
  for (int n : nodes) {
    CHECK(s.node(n).alive);
    CHECK(s.node(n).front == f);
    CHECK(s.node(s.node(n).next).prev == n);
    if (s.node(n).vertex == first && start < 0) start = n;
  }
  REQUIRE(start >= 0);
  std::vector<int> out;
  int n = start;
  do {
    out.push_back(s.node(n).vertex);
    n = s.node(n).next;
  } while (n != start);
  return out;
}

int node_of(const FrontSet& s, int f, int vertex) {
  for (int n : s.nodes_of(f))
    if (s.node(n).vertex == vertex) return n;
  return -1;
}

}  // namespace

TEST_CASE("front: replace a point by new points or remove it", "[polygonize][front]") {
  FrontSet s;
  const int f = s.create_front({0, 1, 2, 3, 4, 5});
  s.replace(node_of(s, f, 2), {10, 11});
  CHECK(cycle(s, f, 0) == std::vector<int>{0, 1, 10, 11, 3, 4, 5});
  s.replace(node_of(s, f, 0), {});
  CHECK(cycle(s, f, 1) == std::vector<int>{1, 10, 11, 3, 4, 5});
  s.remove_front(f);
  CHECK_FALSE(s.front_alive(f));
  CHECK(s.alive_front_count() == 0);
}

TEST_CASE("front: split along a chord gives two fronts sharing it in opposite directions", "[polygonize][front]") {
  FrontSet s;
  const int f = s.create_front({0, 1, 2, 3, 4, 5, 6, 7});
  const auto copies = s.split(node_of(s, f, 1), node_of(s, f, 5));
  const int g = s.node(copies.first).front;
  CHECK(g != f);
  CHECK(s.alive_front_count() == 2);
  CHECK(cycle(s, f, 1) == std::vector<int>{1, 2, 3, 4, 5});     // ... 5 -> 1
  CHECK(cycle(s, g, 5) == std::vector<int>{5, 6, 7, 0, 1});     // ... 1 -> 5
  CHECK(s.node(copies.first).vertex == 1);
  CHECK(s.node(copies.second).vertex == 5);
}

TEST_CASE("front: merge through a bridge gives one front walking the bridge both ways", "[polygonize][front]") {
  FrontSet s;
  const int f = s.create_front({0, 1, 2, 3});
  const int g = s.create_front({10, 11, 12});
  s.merge(node_of(s, f, 1), node_of(s, g, 11));
  CHECK_FALSE(s.front_alive(g));
  CHECK(s.alive_front_count() == 1);
  CHECK(cycle(s, f, 0) == std::vector<int>{0, 1, 11, 12, 10, 11, 1, 2, 3});
}
