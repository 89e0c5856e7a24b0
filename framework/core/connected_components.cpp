#include "framework/core/connected_components.hpp"

#include "framework/core/union_find.hpp"

namespace dtsl {

VertexComponents vertex_components(std::size_t vertices, const std::vector<Face>& faces) {
  UnionFind sets(vertices);
  std::vector<char> used(vertices, 0);
  for (const Face& t : faces) {
    sets.unite(t[0], t[1]);
    sets.unite(t[1], t[2]);
    for (const int v : t) used[v] = 1;
  }
  VertexComponents c;
  c.label.assign(vertices, -1);
  std::vector<int> root_label(vertices, -1);
  for (std::size_t v = 0; v < vertices; ++v) {
    if (!used[v]) continue;
    const std::size_t root = sets.find(v);
    if (root_label[root] < 0) root_label[root] = static_cast<int>(c.count++);
    c.label[v] = root_label[root];
  }
  return c;
}

VertexComponents vertex_components(const TriangleMesh& mesh) { return vertex_components(mesh.vertices.size(), mesh.faces); }

std::vector<std::vector<int>> connected_groups(const std::vector<std::vector<int>>& neighbours,
                                               const std::vector<char>& member) {
  std::vector<std::vector<int>> groups;
  std::vector<char> seen(member.size(), 0);
  std::vector<int> stack;
  for (std::size_t seed = 0; seed < member.size(); ++seed) {
    if (!member[seed] || seen[seed]) continue;
    std::vector<int>& group = groups.emplace_back();
    stack.assign(1, static_cast<int>(seed));
    seen[seed] = 1;
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      group.push_back(v);
      for (const int u : neighbours[v])
        if (member[u] && !seen[u]) seen[u] = 1, stack.push_back(u);
    }
  }
  return groups;
}

}  // namespace dtsl
