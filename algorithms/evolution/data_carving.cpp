#include "algorithms/evolution/data_carving.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <initializer_list>
#include <limits>
#include <mutex>

#include "algorithms/evolution/data_distance.hpp"
#include "algorithms/evolution/data_pieces.hpp"
#include "algorithms/evolution/support.hpp"
#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"

namespace dtsl {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
struct VertexInfo {
  double spacing = 0.0;  // the point's local spacing
  int index = -1;        // the point's index in the input
};
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<VertexInfo, Kernel>;
using CellBase = CGAL::Triangulation_cell_base_with_info_3<char, Kernel>;
constexpr char kInside = 0, kFlooded = 1, kReopened = 2;  // a cell's info: which flood reached it
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, CGAL::Triangulation_data_structure_3<VertexBase, CellBase>>;
using Triangles = std::vector<Kernel::Triangle_3>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>>>;

constexpr double kUnbounded = std::numeric_limits<double>::infinity();

// Circumscribed radius of a tetrahedron; unbounded for a flat one (the empty balls through its facets
// grow without bound on one side).
double circumradius(const Point& a, const Point& b, const Point& c, const Point& d) {
  const Vector u = b - a, v = c - a, w = d - a;
  const double det = 2.0 * (u * CGAL::cross_product(v, w));
  const double scale = std::sqrt((u * u) * (v * v) * (w * w));
  if (!(std::abs(det) > 1e-12 * scale)) return kUnbounded;
  const Vector x = ((u * u) * CGAL::cross_product(v, w) + (v * v) * CGAL::cross_product(w, u) +
                    (w * w) * CGAL::cross_product(u, v)) / det;
  return std::sqrt(x * x);
}

// Circumcentre of a triangle; false for a degenerate one.
bool circumcentre(const Point& a, const Point& b, const Point& c, Point& centre) {
  const Vector u = b - a, v = c - a, n = CGAL::cross_product(u, v);
  const double n2 = n * n;
  if (!(n2 > 1e-24 * (u * u) * (v * v))) return false;
  centre = a + CGAL::cross_product((u * u) * v - (v * v) * u, n) / (2.0 * n2);
  return true;
}
// Breadth first from the cells in `queue` into every cell not yet flooded through a facet (cell c, the
// facet opposite its vertex i) that `passes`, marking them; returns how many cells it flooded.
template <class Passes>
int flood(std::deque<Delaunay::Cell_handle>& queue, char mark, const Passes& passes) {
  int flooded = 0;
  while (!queue.empty()) {
    const Delaunay::Cell_handle c = queue.front();
    queue.pop_front();
    for (int i = 0; i < 4; ++i) {
      const Delaunay::Cell_handle n = c->neighbor(i);
      if (n->info() || !passes(c, i)) continue;
      n->info() = mark;
      ++flooded;
      queue.push_back(n);
    }
  }
  return flooded;
}
}  // namespace

struct DataCarving::Impl {
  explicit Impl(const std::vector<Vec3>& points) : data(points) {}
  DataDistance data;  // throws for non-finite coordinates
  Delaunay delaunay;
  std::vector<double> spacing;  // per data point
  std::vector<int> piece;       // per data point (data_pieces.hpp)
  Triangles boundary;
  std::unique_ptr<Tree> tree;
  mutable std::mutex locate_mutex;  // Delaunay::locate walks with a shared random generator
  mutable Delaunay::Cell_handle hint;
  CarvingSummary summary;

  // Which flood reached the cell holding q (kInside, kFlooded, kReopened).
  char cell_at(const Point& q) const {
    const std::lock_guard<std::mutex> lock(locate_mutex);
    hint = delaunay.locate(q, hint);
    return hint->info();
  }

  double cell_radius(Delaunay::Cell_handle c) const {
    if (delaunay.is_infinite(c)) return kUnbounded;
    return circumradius(c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(), c->vertex(3)->point());
  }
  // The radius of the largest ball that passes the facet of c opposite vertex i, through empty space.
  double gate_radius(Delaunay::Cell_handle c, int i) const {
    const Delaunay::Cell_handle n = c->neighbor(i);
    const Point& a = c->vertex((i + 1) & 3)->point();
    const Point& b = c->vertex((i + 2) & 3)->point();
    const Point& d = c->vertex((i + 3) & 3)->point();
    Point centre;
    const double cells = std::min(cell_radius(c), cell_radius(n));
    if (!circumcentre(a, b, d, centre)) return cells;
    const double r2 = CGAL::squared_distance(centre, a);
    const auto outside = [&](Delaunay::Vertex_handle v) {
      return delaunay.is_infinite(v) || CGAL::squared_distance(centre, v->point()) >= r2;
    };
    const bool gabriel = outside(c->vertex(i)) && outside(n->vertex(n->index(c)));
    return gabriel ? std::sqrt(r2) : cells;
  }
};

DataCarving::DataCarving(const std::vector<Vec3>& points, double alpha_spacings) : impl_(std::make_unique<Impl>(points)) {
  if (points.size() < 4) throw AlgorithmError("data carving: fewer than 4 data points");
  if (!(alpha_spacings > 0.0)) throw AlgorithmError("data carving: alpha must be a positive multiple of the spacing");
  Stopwatch clock;
  // One neighbour search gives the local spacing and the data's pieces (data_pieces.hpp).
  const NearestNeighbours neighbours = impl_->data.nearest_neighbours(kSpacingNeighbours);
  impl_->spacing = mean_neighbour_distance(neighbours);
  const std::vector<double>& spacing = impl_->spacing;
  std::vector<double> sorted = spacing;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  CarvingSummary& s = impl_->summary;
  s.spacing = sorted[sorted.size() / 2];
  s.alpha = alpha_spacings;
  if (!(s.spacing > 0.0)) throw AlgorithmError("data carving: the data points coincide (zero spacing)");

  std::vector<std::pair<Point, VertexInfo>> input;
  input.reserve(points.size());
  for (std::size_t k = 0; k < points.size(); ++k)
    input.emplace_back(Point(points[k].x(), points[k].y(), points[k].z()), VertexInfo{spacing[k], int(k)});
  Delaunay& dt = impl_->delaunay;
  dt.insert(input.begin(), input.end());
  if (dt.dimension() < 3) throw AlgorithmError("data carving: the data points are coplanar");

  // Flood from the infinite cells (breadth first; a cell is flooded once).
  std::deque<Delaunay::Cell_handle> queue;
  for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c) {
    c->info() = dt.is_infinite(c) ? kFlooded : kInside;
    if (c->info()) queue.push_back(c);
  }
  flood(queue, kFlooded, [&](Delaunay::Cell_handle c, int i) {
    double local = 0.0;
    for (int k = 1; k < 4; ++k) local = std::max(local, c->vertex((i + k) & 3)->info().spacing);
    return impl_->gate_radius(c, i) >= alpha_spacings * local;
  });
  // Second flood: on from the flooded cells through every facet whose corners lie on different pieces of
  // the data, however narrow (see the header).
  impl_->piece = data_pieces(neighbours);
  const std::vector<int>& piece = impl_->piece;
  s.data_pieces = 1 + *std::max_element(piece.begin(), piece.end());
  const auto pieces_differ = [&](std::initializer_list<Delaunay::Vertex_handle> corners) {
    int first = -1;
    for (const Delaunay::Vertex_handle v : corners) {
      if (dt.is_infinite(v)) continue;
      const int p = piece[std::size_t(v->info().index)];
      if (first < 0) first = p;
      else if (p != first) return true;
    }
    return false;
  };
  if (s.data_pieces > 1) {
    for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c)
      if (c->info()) queue.push_back(c);
    s.reopened_cells = flood(queue, kReopened, [&](Delaunay::Cell_handle c, int i) {
      return pieces_differ({c->vertex((i + 1) & 3), c->vertex((i + 2) & 3), c->vertex((i + 3) & 3)});
    });
  }
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
    if (c->info()) continue;
    ++s.inside_cells;
    for (int i = 0; i < 4; ++i)
      if (c->neighbor(i)->info())
        impl_->boundary.emplace_back(c->vertex((i + 1) & 3)->point(), c->vertex((i + 2) & 3)->point(),
                                     c->vertex((i + 3) & 3)->point());
  }
  s.boundary_facets = int(impl_->boundary.size());
  if (!impl_->boundary.empty()) {
    impl_->tree = std::make_unique<Tree>(impl_->boundary.begin(), impl_->boundary.end());
    impl_->tree->accelerate_distance_queries();
  }
  impl_->hint = dt.infinite_cell();
  s.seconds = clock.seconds();
}

DataCarving::~DataCarving() = default;

CarvingValue DataCarving::evaluate(const Vec3& x) const {
  const Point q(x.x(), x.y(), x.z());
  const NearestData nearest = impl_->data.nearest(x);
  const double to_data = nearest.distance;
  const int piece = impl_->piece[std::size_t(nearest.index)];
  if (!impl_->tree) return {to_data, piece};  // all carved (data without volume): outside everywhere
  const double d = std::sqrt(impl_->tree->squared_distance(q));
  const char cell = impl_->cell_at(q);
  // Outside, data the flood passed on both sides (an open sheet, a sparse strand) are as near as the boundary.
  return {cell != kInside ? std::min(d, to_data) : -d, piece};
}

double DataCarving::operator()(const Vec3& x) const { return evaluate(x).distance; }

bool DataCarving::reopened(const Vec3& x) const { return impl_->cell_at(Point(x.x(), x.y(), x.z())) == kReopened; }

const CarvingSummary& DataCarving::summary() const { return impl_->summary; }

const std::vector<double>& DataCarving::local_spacing() const { return impl_->spacing; }

const std::vector<int>& DataCarving::pieces() const { return impl_->piece; }

}  // namespace dtsl
