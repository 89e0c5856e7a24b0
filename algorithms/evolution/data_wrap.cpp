#include "algorithms/evolution/data_wrap.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/alpha_wrap_3.h>

#include <algorithm>
#include <cmath>

#include "algorithms/evolution/data_distance.hpp"
#include "algorithms/evolution/support.hpp"
#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"

namespace dtsl {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using WrapMesh = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<WrapMesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
using Inside = CGAL::Side_of_triangle_mesh<WrapMesh, Kernel>;
}  // namespace

struct DataWrap::Impl {
  WrapMesh mesh;
  std::unique_ptr<Tree> tree;
  std::unique_ptr<Inside> inside;
  WrapSummary summary;
};

DataWrap::DataWrap(const std::vector<Vec3>& points, double alpha_spacings, double offset_spacings)
    : impl_(std::make_unique<Impl>()) {
  if (points.size() < 4) throw AlgorithmError("data wrap: fewer than 4 data points");
  if (!(alpha_spacings > 0.0) || !(offset_spacings > 0.0))
    throw AlgorithmError("data wrap: alpha and offset must be positive multiples of the spacing");
  Stopwatch clock;
  const DataDistance distance(points);  // throws for non-finite coordinates
  std::vector<double> spacing = distance.local_spacing(kSpacingNeighbours);
  std::nth_element(spacing.begin(), spacing.begin() + spacing.size() / 2, spacing.end());
  WrapSummary& s = impl_->summary;
  s.spacing = spacing[spacing.size() / 2];
  if (!(s.spacing > 0.0)) throw AlgorithmError("data wrap: the data points coincide (zero spacing)");
  s.alpha = alpha_spacings * s.spacing;
  s.offset = offset_spacings * s.spacing;

  std::vector<Point> cgal_points;
  cgal_points.reserve(points.size());
  for (const Vec3& p : points) cgal_points.emplace_back(p.x(), p.y(), p.z());
  CGAL::alpha_wrap_3(cgal_points, s.alpha, s.offset, impl_->mesh);
  WrapMesh& mesh = impl_->mesh;
  if (mesh.number_of_faces() == 0) throw AlgorithmError("data wrap: the wrap is empty");

  auto component = mesh.add_property_map<WrapMesh::Face_index, std::size_t>("f:component").first;
  s.components = int(CGAL::Polygon_mesh_processing::connected_components(mesh, component));
  const long euler = long(mesh.number_of_vertices()) - long(mesh.number_of_edges()) + long(mesh.number_of_faces());
  s.genus = int((2 * long(s.components) - euler) / 2);
  s.vertices = int(mesh.number_of_vertices());
  s.faces = int(mesh.number_of_faces());

  impl_->tree = std::make_unique<Tree>(faces(mesh).first, faces(mesh).second, mesh);
  impl_->tree->accelerate_distance_queries();
  impl_->inside = std::make_unique<Inside>(*impl_->tree);
  s.seconds = clock.seconds();
}

DataWrap::~DataWrap() = default;

double DataWrap::operator()(const Vec3& x) const {
  const Point q(x.x(), x.y(), x.z());
  const double d = std::sqrt(impl_->tree->squared_distance(q));
  return (*impl_->inside)(q) == CGAL::ON_BOUNDED_SIDE ? -d : d;
}

const WrapSummary& DataWrap::summary() const { return impl_->summary; }

}  // namespace dtsl
