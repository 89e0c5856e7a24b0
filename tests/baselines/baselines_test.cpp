// The PCL baselines through the registry, as an experiment uses them: each reconstructs a sampled
// sphere, reports its normal source and stages, and refuses bad input with an AlgorithmError (never a
// crash) and bad options with a ConfigError naming the field.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "algorithms/baselines/baseline.hpp"
#include "experiments/plugins.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "framework/metrics/metrics.hpp"
#include "framework/pipeline/reconstructor.hpp"
#include "tests/baselines/pipeline_helpers.hpp"

namespace {

using namespace dtsl;
using Catch::Matchers::Contains;

const std::vector<std::string> kBaselines = {"pcl_poisson", "pcl_mc_hoppe", "pcl_mc_rbf", "pcl_gp3", "pcl_grid"};
constexpr double kRadius = 0.95;

// n points uniform on the sphere of radius kRadius (so the cloud fills the [-1,1]^3 frame), with exact
// outward normals if `normals`.
PointCloud sphere(std::size_t n, bool normals = true, std::uint64_t seed = 7) {
  return test::sampled_sphere(n, kRadius, normals, seed);
}

using test::create;
using test::set;
using test::signed_volume;

struct RadialError {
  double mean = 0.0, max = 0.0;
};
RadialError radial_error(const TriangleMesh& m) {
  RadialError e;
  for (const Vec3& v : m.vertices) {
    const double d = std::abs(v.norm() - kRadius);
    e.mean += d;
    e.max = std::max(e.max, d);
  }
  e.mean /= std::max<std::size_t>(1, m.vertices.size());
  return e;
}

}  // namespace

TEST_CASE("every PCL baseline is registered with documented options", "[baselines]") {
  register_all_plugins();
  register_all_plugins();  // idempotent
  for (const std::string& name : kBaselines) {
    INFO(name);
    REQUIRE(reconstructors().contains(name));
    auto r = reconstructors().create(name, "test");
    const auto fields = describe(r->options());
    CHECK(fields.size() >= 5);
    bool has_normals = false;
    for (const FieldDescription& f : fields) {
      INFO(f.name);
      CHECK(!f.doc.empty());
      has_normals = has_normals || f.name == "normals";
    }
    CHECK(has_normals);
    CHECK_NOTHROW(r->options().check());
  }
}

TEST_CASE("each baseline reconstructs a sampled sphere", "[baselines]") {
  // Tolerances on the mean |r - R| of the mesh vertices (R = 0.95; measured: Poisson 4e-4, Hoppe
  // 6e-4, RBF 1e-4, grid 2e-3; GP3's vertices are input points). Grid projection stops its bisection
  // at |d| < 0.01 of PCL's unit cube, and at its default resolution it needs ~5000 points on this
  // sphere not to tear; the RBF gets 1000 points to keep its dense system small.
  struct Case {
    std::string name;
    std::size_t points;
    double tolerance;
    bool watertight;
  };
  const Case c = GENERATE(Case{"pcl_poisson", 3000, 0.01, true}, Case{"pcl_mc_hoppe", 3000, 0.01, true},
                          Case{"pcl_mc_rbf", 1000, 0.01, true},  // dense 2000 x 2000 system
                          Case{"pcl_gp3", 3000, 1e-9, false},
                          Case{"pcl_grid", 5000, 0.01, false});  // tears below ~5000 at resolution 0.03
  INFO(c.name);
  auto r = create(c.name);
  const PointCloud cloud = sphere(c.points);
  const ReconstructionResult result = r->reconstruct(cloud, RunContext{});

  REQUIRE(!result.mesh.faces.empty());
  CHECK(result.mesh.vertices.size() >= 100);
  const RadialError e = radial_error(result.mesh);
  INFO("mean |r - R| = " << e.mean << ", max = " << e.max);
  CHECK(e.mean < c.tolerance);
  CHECK(e.max < 0.1);

  CHECK(result.summary.at("normals_source") == "ground_truth");
  const StageRecord& normals = stage(result, "normals");
  const StageRecord& recon = stage(result, "reconstruct");
  CHECK(normals.seconds >= 0.0);
  CHECK(recon.seconds > 0.0);
  CHECK(recon.summary.at("faces") == result.mesh.faces.size());
  CHECK(recon.summary.at("vertices") == result.mesh.vertices.size());

  const MeshStats s = mesh_stats(result.mesh);
  INFO("boundary edges " << s.boundary_edges << ", non-manifold edges " << s.nonmanifold_edges
                         << ", components " << s.components);
  CHECK(s.degenerate_faces <= result.mesh.faces.size() / 100);
  if (c.watertight) {
    CHECK(s.watertight);
    CHECK(s.components == 1);
    CHECK(s.genus == Approx(0.0));
  }
  // Consistently outward: the signed volume is close to the ball's (open meshes: loosely).
  const double ball = 4.0 / 3.0 * M_PI * std::pow(kRadius, 3);
  CHECK(signed_volume(result.mesh) > (c.watertight ? 0.9 : 0.5) * ball);
}

TEST_CASE("estimated normals are used and reported when the cloud has none", "[baselines]") {
  const std::string name = GENERATE(std::string("pcl_poisson"), std::string("pcl_mc_hoppe"));
  INFO(name);
  auto r = create(name);
  const std::string source = GENERATE(std::string("auto"), std::string("jet_mst"));
  set(*r, "normals", source);
  const ReconstructionResult result = r->reconstruct(sphere(3000, false), RunContext{});
  CHECK(result.summary.at("normals_source") == "jet_mst");
  CHECK(radial_error(result.mesh).mean < 0.01);
  CHECK(mesh_stats(result.mesh).watertight);
  CHECK(signed_volume(result.mesh) > 0.0);  // MST orientation points outward
}

TEST_CASE("normals: ground_truth on a cloud without normals is refused naming the option", "[baselines]") {
  const std::string name = GENERATE(from_range(kBaselines));
  INFO(name);
  auto r = create(name);
  set(*r, "normals", "ground_truth");
  CHECK_THROWS_AS(r->reconstruct(sphere(500, false), RunContext{}), AlgorithmError);
  CHECK_THROWS_WITH(r->reconstruct(sphere(500, false), RunContext{}),
                    Contains(name) && Contains("normals") && Contains("ground_truth"));
}

TEST_CASE("pcl_mc_rbf: the fast solver matches PCL's own, and threads do not change the result", "[baselines]") {
  const PointCloud cloud = sphere(300);
  auto fast = create("pcl_mc_rbf");
  set(*fast, "grid_resolution", "24");
  auto exact = create("pcl_mc_rbf");
  set(*exact, "grid_resolution", "24");
  set(*exact, "rbf_solver", "pcl");
  const TriangleMesh a = fast->reconstruct(cloud, RunContext{1, 1}).mesh;
  const TriangleMesh b = exact->reconstruct(cloud, RunContext{1, 1}).mesh;
  const TriangleMesh c = fast->reconstruct(cloud, RunContext{1, 2}).mesh;
  REQUIRE(a.vertices.size() == b.vertices.size());
  REQUIRE(a.faces == b.faces);
  double worst = 0.0;
  for (std::size_t i = 0; i < a.vertices.size(); ++i) worst = std::max(worst, (a.vertices[i] - b.vertices[i]).norm());
  CHECK(worst < 1e-4);
  REQUIRE(a.vertices.size() == c.vertices.size());
  CHECK(a.faces == c.faces);
}

TEST_CASE("pcl_mc_rbf refuses more than max_points, naming the count, the limit and the option", "[baselines]") {
  auto r = create("pcl_mc_rbf");
  set(*r, "max_points", "300");
  try {
    r->reconstruct(sphere(301), RunContext{});
    FAIL("no exception");
  } catch (const AlgorithmError& e) {
    const std::string m = e.what();
    CHECK_THAT(m, Contains("pcl_mc_rbf") && Contains("301") && Contains("300") && Contains("max_points"));
  }
  // The default limit refuses a 5000-point cloud before spending any time on it.
  auto d = create("pcl_mc_rbf");
  CHECK_THROWS_WITH(d->reconstruct(sphere(5000), RunContext{}), Contains("max_points = 4000"));
}

TEST_CASE("too few points are an AlgorithmError naming the method and the count", "[baselines]") {
  const std::string name = GENERATE(from_range(kBaselines));
  const std::size_t n = GENERATE(0, 1, 3);
  INFO(name << " with " << n << " points");
  auto r = create(name);
  CHECK_THROWS_AS(r->reconstruct(sphere(n), RunContext{}), AlgorithmError);
  CHECK_THROWS_WITH(r->reconstruct(sphere(n), RunContext{}),
                    Contains(name) && Contains("got " + std::to_string(n)));
}

TEST_CASE("degenerate point sets are refused before PCL sees them", "[baselines]") {
  const std::string name = GENERATE(from_range(kBaselines));
  INFO(name);
  auto r = create(name);

  SECTION("all points coincide") {
    PointCloud c;
    c.points.assign(1000, Vec3(0.5, 0.5, 0.5));
    c.normals.assign(1000, Vec3(0, 0, 1));
    CHECK_THROWS_WITH(r->reconstruct(c, RunContext{}), Contains("distinct points, got 1"));
  }
  SECTION("collinear points") {
    PointCloud c;
    for (int i = 0; i < 500; ++i) {
      c.points.push_back(Vec3(-1.0 + i * 0.004, 0.5 * (-1.0 + i * 0.004), 0.25));
      c.normals.push_back(Vec3(0, 0, 1));
    }
    CHECK_THROWS_WITH(r->reconstruct(c, RunContext{}), Contains("collinear"));
  }
  SECTION("a NaN coordinate") {
    PointCloud c = sphere(500);
    c.points[17].y() = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_WITH(r->reconstruct(c, RunContext{}), Contains("17") && Contains(name));
  }
  SECTION("an infinite normal") {
    PointCloud c = sphere(500);
    c.normals[3].x() = std::numeric_limits<double>::infinity();
    CHECK_THROWS_AS(r->reconstruct(c, RunContext{}), AlgorithmError);
  }
}

TEST_CASE("coplanar points: volumetric methods refuse, surface methods triangulate", "[baselines]") {
  // A tilted disc, so no bounding-box side is zero: only the principal extents reveal the plane.
  PointCloud disc;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec3 n = Vec3(1, 2, 3).normalized();
  const Vec3 a = n.unitOrthogonal(), b = n.cross(a);
  while (disc.size() < 2000) {
    const double x = u(rng), y = u(rng);
    if (x * x + y * y > 1.0) continue;
    disc.points.push_back(0.9 * (x * a + y * b));
    disc.normals.push_back(n);
  }
  for (const std::string name : {"pcl_poisson", "pcl_mc_hoppe", "pcl_mc_rbf"}) {
    INFO(name);
    CHECK_THROWS_WITH(create(name)->reconstruct(disc, RunContext{}), Contains("coplanar") && Contains(name));
  }
  const ReconstructionResult gp3 = create("pcl_gp3")->reconstruct(disc, RunContext{});
  CHECK(gp3.mesh.faces.size() > 1000);
}

TEST_CASE("duplicated points are merged and counted", "[baselines]") {
  PointCloud c = sphere(2000);
  const PointCloud copy = c;
  c.points.insert(c.points.end(), copy.points.begin(), copy.points.end());
  c.normals.insert(c.normals.end(), copy.normals.begin(), copy.normals.end());
  const ReconstructionResult r = create("pcl_gp3")->reconstruct(c, RunContext{});
  CHECK(r.summary.at("duplicates_removed") == 2000);
  CHECK(r.mesh.faces.size() > 3000);  // PCL's GP3 alone returns no triangle on this input
}

TEST_CASE("pcl_grid refuses a resolution whose grid is too large", "[baselines]") {
  auto r = create("pcl_grid");
  set(*r, "resolution", "0.001");
  CHECK_THROWS_WITH(r->reconstruct(sphere(500), RunContext{}),
                    Contains("max_grid_cells") && Contains("resolution"));
}

TEST_CASE("an empty result is an AlgorithmError that names the method", "[baselines]") {
  // GP3 with edges shorter than the point spacing (~0.1 at 1000 points) finds no triangle.
  auto r = create("pcl_gp3");
  set(*r, "search_radius", "0.001");
  CHECK_THROWS_WITH(r->reconstruct(sphere(1000), RunContext{}),
                    Contains("pcl_gp3 produced no triangles") && Contains("search_radius"));
}

TEST_CASE("option checks name the field and the rule", "[baselines]") {
  const std::map<std::string, std::vector<std::pair<std::string, std::string>>> bad = {
      {"pcl_poisson",
       {{"depth", "20"}, {"depth", "1"}, {"min_depth", "9"}, {"point_weight", "-1"}, {"scale", "0.5"},
        {"samples_per_node", "0"}, {"solver_divide", "2"}, {"iso_divide", "40"}, {"degree", "6"},
        {"normals", "magic"}}},
      {"pcl_mc_hoppe",
       {{"grid_resolution", "4"}, {"grid_resolution", "100000"}, {"iso_level", "1"}, {"iso_level", "-0.5"},
        {"percentage_extend_grid", "-0.1"}, {"dist_ignore", "-1"}}},
      {"pcl_mc_rbf",
       {{"grid_resolution", "0"}, {"off_surface_displacement", "0"}, {"max_points", "5"},
        {"max_points", "1000000"}, {"rbf_solver", "cholesky"}}},
      {"pcl_gp3",
       {{"search_radius", "0"}, {"mu", "-1"}, {"max_nearest_neighbors", "2"}, {"max_surface_angle_deg", "200"},
        {"min_angle_deg", "70"}, {"max_angle_deg", "30"}}},
      {"pcl_grid",
       {{"resolution", "0"}, {"padding_size", "0"}, {"nearest_neighbors", "0"}, {"max_binary_search_level", "0"},
        {"max_grid_cells", "10"}}},
  };
  for (const auto& [name, cases] : bad)
    for (const auto& [key, value] : cases) {
      INFO(name << ": " << key << " = " << value);
      auto r = create(name);
      CHECK_THROWS_AS(set(*r, key, value), ConfigError);
      auto fresh = create(name);
      CHECK_THROWS_WITH(set(*fresh, key, value), Contains(key));
    }
  // A rule that involves two fields is reported on the one being set.
  auto gp3 = create("pcl_gp3");
  set(*gp3, "max_angle_deg", "60");
  CHECK_THROWS_WITH(set(*gp3, "min_angle_deg", "60"), Contains("min_angle_deg") && Contains("max_angle_deg"));
}

TEST_CASE("soup_to_mesh fan-triangulates, welds and drops what no mesh should hold", "[baselines]") {
  using namespace dtsl::baselines;
  PolygonSoup soup;
  // A unit square as a quad, a second copy of its corner 2 (to be welded), an unused vertex, a
  // triangle with a repeated index, one with an out-of-range index, and a duplicate of the first.
  soup.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), Vec3(1, 1, 1e-9), Vec3(5, 5, 5)};
  soup.polygons = {{0, 1, 2, 3}, {0, 4, 3}, {1, 1, 2}, {0, 2, 9}, {1, 2, 0}};
  CleanupCounts counts;
  const TriangleMesh m = soup_to_mesh(soup, 1e-6, false, &counts);
  CHECK(m.faces.size() == 2);
  CHECK(m.vertices.size() == 4);
  CHECK(counts.triangles == 6);
  CHECK(counts.welded == 1);
  CHECK(counts.degenerate_dropped == 1);
  CHECK(counts.invalid_dropped == 1);
  CHECK(counts.duplicate_dropped == 2);  // {0,4,3} == {0,2,3} after welding, and {1,2,0}
  CHECK(counts.unreferenced_removed == 1);
  const TriangleMesh flipped = soup_to_mesh(soup, 1e-6, true, nullptr);
  CHECK(flipped.faces[0] == Face{0, 2, 1});
}
