// The front polygons of Hartmann's marching method (Hartmann 1998, "A marching method for the
// triangulation of surfaces", The Visual Computer 14:95-108; the paper's ref [21]): closed cyclic lists
// of mesh vertices bounding the triangulated region. Pure bookkeeping — no geometry — so the operations
// the marcher relies on (replace a point by new points, split a front by a chord, merge two fronts by a
// bridge) can be reasoned about and tested on their own.
//
// Orientation convention: the triangle behind a front edge a->b (already made) contains a->b in that
// direction, so the triangle later made in front of it contains b->a, and all faces come out
// consistently oriented with outward normals (counter-clockwise seen from outside). The free
// (untriangulated) region at a front point p lies counter-clockwise about the normal from the direction
// of prev(p) to the direction of next(p); that angle is p's front angle.
#pragma once

#include <utility>
#include <vector>

namespace dtsl {

struct FrontNode {
  int vertex = -1;  ///< mesh vertex; a vertex can appear in several nodes after a split or merge
  int prev = -1, next = -1;
  int front = -1;
  double angle = 0.0;  ///< front angle (radians), kept current by the marcher
  int version = 0;     ///< bumped on every angle update: stale heap entries are recognised by it
  bool alive = false;
  bool frozen = false;  ///< outside f's domain: never expanded, the front stays open there
};

class FrontSet {
 public:
  /// A new front through `vertices` in order (at least 3); returns its id.
  int create_front(const std::vector<int>& vertices);

  const FrontNode& node(int i) const { return nodes_[static_cast<std::size_t>(i)]; }
  FrontNode& node(int i) { return nodes_[static_cast<std::size_t>(i)]; }
  int front_size(int f) const { return fronts_[static_cast<std::size_t>(f)].size; }
  bool front_alive(int f) const { return fronts_[static_cast<std::size_t>(f)].alive; }
  int front_count() const { return static_cast<int>(fronts_.size()); }
  int alive_front_count() const;

  /// The nodes of front f in order, starting anywhere.
  std::vector<int> nodes_of(int f) const;

  /// Replaces node m by new nodes for `vertices` (in front order between prev(m) and next(m); empty
  /// removes m). Returns the new node ids. m dies.
  std::vector<int> replace(int m, const std::vector<int>& vertices);

  /// Splits the front holding m and j (non-adjacent) along the chord m-j into
  ///   m -> ... -> j -> m      (keeps the front id; the chord runs j->m)
  ///   j' -> ... -> m' -> j'   (a new front; copies m', j' of m and j; the chord runs m'->j')
  /// Returns {m', j'}.
  std::pair<int, int> split(int m, int j);

  /// Merges the front of j into the front of m (different fronts) through the bridge m-j:
  ///   ... prev(m) -> m -> j -> next(j) ... prev(j) -> j' -> m' -> next(m) ...
  /// Returns {m', j'} (the copies). The front of j dies.
  std::pair<int, int> merge(int m, int j);

  /// Kills front f and all its nodes.
  void remove_front(int f);

 private:
  struct Front {
    int head = -1;
    int size = 0;
    bool alive = false;
  };
  int new_node(int vertex, int front);
  void relabel(int start, int front);  // sets front on the cycle through start; returns nothing

  std::vector<FrontNode> nodes_;
  std::vector<Front> fronts_;
};

}  // namespace dtsl
