#include "algorithms/polygonize/front.hpp"

#include "framework/core/error.hpp"

namespace dtsl {

int FrontSet::new_node(int vertex, int front) {
  FrontNode n;
  n.vertex = vertex;
  n.front = front;
  n.alive = true;
  nodes_.push_back(n);
  return static_cast<int>(nodes_.size()) - 1;
}

int FrontSet::create_front(const std::vector<int>& vertices) {
  if (vertices.size() < 3) throw AlgorithmError("front: a front needs at least 3 points");
  const int f = static_cast<int>(fronts_.size());
  fronts_.push_back(Front{-1, static_cast<int>(vertices.size()), true});
  std::vector<int> ids;
  for (int v : vertices) ids.push_back(new_node(v, f));
  const std::size_t n = ids.size();
  for (std::size_t i = 0; i < n; ++i) {
    node(ids[i]).next = ids[(i + 1) % n];
    node(ids[i]).prev = ids[(i + n - 1) % n];
  }
  fronts_.back().head = ids[0];
  return f;
}

int FrontSet::alive_front_count() const {
  int c = 0;
  for (const Front& f : fronts_) c += f.alive ? 1 : 0;
  return c;
}

std::vector<int> FrontSet::nodes_of(int f) const {
  std::vector<int> out;
  const Front& fr = fronts_[static_cast<std::size_t>(f)];
  if (!fr.alive) return out;
  int i = fr.head;
  do {
    out.push_back(i);
    i = node(i).next;
    // A broken cycle would loop forever; the size bounds the walk.
    if (static_cast<int>(out.size()) > fr.size) throw AlgorithmError("front: inconsistent front cycle");
  } while (i != fr.head);
  return out;
}

std::vector<int> FrontSet::replace(int m, const std::vector<int>& vertices) {
  FrontNode& old = node(m);
  const int f = old.front, p = old.prev, n = old.next;
  std::vector<int> ids;
  int last = p;
  for (int v : vertices) {
    const int id = new_node(v, f);  // may reallocate nodes_: no references kept across this
    node(id).prev = last;
    node(last).next = id;
    ids.push_back(id);
    last = id;
  }
  node(last).next = n;
  node(n).prev = last;
  node(m).alive = false;
  Front& fr = fronts_[static_cast<std::size_t>(f)];
  fr.size += static_cast<int>(vertices.size()) - 1;
  if (fr.head == m) fr.head = n;
  return ids;
}

void FrontSet::relabel(int start, int front) {
  int i = start, count = 0;
  do {
    node(i).front = front;
    i = node(i).next;
    ++count;
  } while (i != start);
  fronts_[static_cast<std::size_t>(front)].size = count;
  fronts_[static_cast<std::size_t>(front)].head = start;
}

std::pair<int, int> FrontSet::split(int m, int j) {
  const int f = node(m).front;
  if (node(j).front != f) throw AlgorithmError("front: split of points on different fronts");
  const int pm = node(m).prev, nj = node(j).next;
  const int g = static_cast<int>(fronts_.size());
  fronts_.push_back(Front{-1, 0, true});
  const int m2 = new_node(node(m).vertex, g);
  const int j2 = new_node(node(j).vertex, g);
  // Second front: j' -> next(j) ... prev(m) -> m' -> j'.
  node(j2).next = nj;
  node(nj).prev = j2;
  node(pm).next = m2;
  node(m2).prev = pm;
  node(m2).next = j2;
  node(j2).prev = m2;
  // First front: m -> ... -> j -> m.
  node(j).next = m;
  node(m).prev = j;
  relabel(m, f);
  relabel(j2, g);
  return {m2, j2};
}

std::pair<int, int> FrontSet::merge(int m, int j) {
  const int f = node(m).front, g = node(j).front;
  if (f == g) throw AlgorithmError("front: merge of points on the same front");
  const int nm = node(m).next, pj = node(j).prev;
  const int m2 = new_node(node(m).vertex, f);
  const int j2 = new_node(node(j).vertex, f);
  node(m).next = j;
  node(j).prev = m;
  node(pj).next = j2;
  node(j2).prev = pj;
  node(j2).next = m2;
  node(m2).prev = j2;
  node(m2).next = nm;
  node(nm).prev = m2;
  fronts_[static_cast<std::size_t>(g)].alive = false;
  relabel(m, f);
  return {m2, j2};
}

void FrontSet::remove_front(int f) {
  for (int i : nodes_of(f)) node(i).alive = false;
  fronts_[static_cast<std::size_t>(f)].alive = false;
  fronts_[static_cast<std::size_t>(f)].size = 0;
}

}  // namespace dtsl
