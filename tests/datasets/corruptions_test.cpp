// Corruptions: each does what it says — noise of the configured spread, empty holes, an empty side of
// the cutting plane, outliers in the box, a subset of the requested size — and is a function of its
// generator alone.
#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <set>

#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "framework/datasets/dataset.hpp"

using namespace dtsl;

namespace {

std::unique_ptr<Corruption> make(const std::string& type, const std::string& yaml = "{}") {
  register_dataset_plugins();
  auto p = corruptions().create(type, "c");
  apply_yaml(p->options(), YAML::Load(yaml), "c");
  return p;
}

/// 20k area-uniform points with normals on the unit sphere.
PointCloud sphere_points(std::size_t count = 20000) {
  register_dataset_plugins();
  auto shape = shape_sources().create("sphere", "s");
  const ShapeData d = shape->load();
  auto sampler = samplers().create("area", "s");
  apply_yaml(sampler->options(), YAML::Load("{count: " + std::to_string(count) + "}"), "s");
  std::mt19937_64 rng(5);
  return sampler->sample(d, rng);
}

PointCloud applied(const std::string& type, const std::string& yaml, PointCloud cloud, std::uint64_t seed = 9) {
  std::mt19937_64 rng(seed);
  make(type, yaml)->apply(cloud, rng);
  return cloud;
}

using Key = std::tuple<double, double, double>;
Key key(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

}  // namespace

TEST_CASE("noise: isotropic Gaussian with the configured sigma, normals kept", "[datasets][corruptions]") {
  const PointCloud clean = sphere_points();
  const PointCloud noisy = applied("noise", "{sigma: 0.01}", clean);
  REQUIRE(noisy.size() == clean.size());
  CHECK(noisy.normals == clean.normals);
  Vec3 mean = Vec3::Zero(), sq = Vec3::Zero();
  for (std::size_t i = 0; i < clean.size(); ++i) {
    const Vec3 d = noisy.points[i] - clean.points[i];
    mean += d;
    sq += d.cwiseProduct(d);
  }
  const double n = static_cast<double>(clean.size());
  mean /= n;
  const Vec3 sd = (sq / n - mean.cwiseProduct(mean)).cwiseSqrt();
  INFO("mean " << mean.transpose() << ", sd " << sd.transpose());
  for (int k = 0; k < 3; ++k) {
    CHECK(std::abs(mean[k]) < 3e-4);  // 4 standard errors (0.01 / sqrt(20000) = 7e-5)
    CHECK(sd[k] == Approx(0.01).epsilon(0.03));
  }
}

TEST_CASE("noise: along the normal moves points along their normal only", "[datasets][corruptions]") {
  const PointCloud clean = sphere_points();
  const PointCloud noisy = applied("noise", "{sigma: 0.02, direction: normal}", clean);
  double sq = 0;
  for (std::size_t i = 0; i < clean.size(); ++i) {
    const Vec3 d = noisy.points[i] - clean.points[i];
    REQUIRE(d.cross(clean.normals[i]).norm() < 1e-12);
    sq += d.squaredNorm();
  }
  CHECK(std::sqrt(sq / clean.size()) == Approx(0.02).epsilon(0.03));

  PointCloud bare;
  bare.points = clean.points;
  std::mt19937_64 rng(1);
  CHECK_THROWS_AS(make("noise", "{direction: normal}")->apply(bare, rng), AlgorithmError);
}

TEST_CASE("holes: the balls are empty and nothing else is removed", "[datasets][corruptions]") {
  const PointCloud clean = sphere_points();
  auto holes = make("holes", "{count: 4, radius: 0.25}");
  PointCloud cut = clean;
  std::mt19937_64 rng(3);
  holes->apply(cut, rng);
  const nlohmann::json report = holes->report();
  REQUIRE(report["centres"].size() == 4);
  std::vector<Vec3> centres;
  for (const auto& c : report["centres"]) centres.emplace_back(c[0], c[1], c[2]);

  auto in_a_hole = [&](const Vec3& p) {
    for (const Vec3& c : centres)
      if ((p - c).norm() <= 0.25) return true;
    return false;
  };
  std::size_t outside = 0;
  for (const Vec3& p : clean.points) outside += in_a_hole(p) ? 0 : 1;
  for (const Vec3& p : cut.points) REQUIRE_FALSE(in_a_hole(p));
  CHECK(cut.size() == outside);
  CHECK(cut.size() < clean.size());
  REQUIRE(cut.has_normals());
  // Each hole takes about (area of a spherical cap of chord radius 0.25) / 4 pi of the points.
  CHECK(clean.size() - cut.size() > 400);
}

TEST_CASE("plane_cut: the positive side is empty, the other side untouched", "[datasets][corruptions]") {
  const PointCloud clean = sphere_points();
  const PointCloud cut = applied("plane_cut", "{normal: [1, 1, 0], offset: 0.2}", clean);
  const Vec3 n = Vec3(1, 1, 0).normalized();
  std::size_t below = 0;
  for (const Vec3& p : clean.points) below += n.dot(p) <= 0.2 ? 1 : 0;
  for (const Vec3& p : cut.points) REQUIRE(n.dot(p) <= 0.2);
  CHECK(cut.size() == below);
  // A plane at distance 0.2 from the centre leaves (1 + 0.2) / 2 of a sphere's area (Archimedes).
  CHECK(static_cast<double>(cut.size()) / clean.size() == Approx(0.6).epsilon(0.03));
}

TEST_CASE("outliers: the fraction added, uniform in the box, with unit normals", "[datasets][corruptions]") {
  const PointCloud clean = sphere_points();
  auto outliers = make("outliers", "{fraction: 0.1}");
  PointCloud noisy = clean;
  std::mt19937_64 rng(2);
  outliers->apply(noisy, rng);
  REQUIRE(noisy.size() == clean.size() + 2000);
  CHECK(outliers->report()["added"] == 2000);
  REQUIRE(noisy.has_normals());
  const BoundingBox box = bounding_box(clean.points);
  std::size_t off_surface = 0;
  for (std::size_t i = clean.size(); i < noisy.size(); ++i) {
    const Vec3& p = noisy.points[i];
    REQUIRE(((p.array() >= box.min.array()).all() && (p.array() <= box.max.array()).all()));
    REQUIRE(std::abs(noisy.normals[i].norm() - 1.0) < 1e-12);
    off_surface += std::abs(p.norm() - 1.0) > 0.05 ? 1 : 0;
  }
  // A uniform point of the cube [-1,1]^3 is within 0.05 of the unit sphere with probability about
  // (4 pi 0.1 - the shell's parts outside the cube) / 8 = 0.145.
  CHECK(off_surface > 1600);
  for (std::size_t i = 0; i < clean.size(); ++i) REQUIRE(noisy.points[i] == clean.points[i]);

  // With a margin the box grows by margin x its size on every side.
  const PointCloud wide = applied("outliers", "{fraction: 1, margin: 0.5}", clean);
  const BoundingBox wbox = bounding_box(wide.points);
  CHECK(wbox.extent().minCoeff() > 3.0);
  CHECK(wbox.extent().maxCoeff() <= 4.0 + 1e-12);
}

TEST_CASE("subsample: exactly count points, a subset in the original order", "[datasets][corruptions]") {
  const PointCloud clean = sphere_points();
  const PointCloud sub = applied("subsample", "{count: 6000}", clean);
  REQUIRE(sub.size() == 6000);
  REQUIRE(sub.has_normals());
  std::size_t j = 0;  // each kept point appears in the original, later than the previous one
  for (std::size_t i = 0; i < sub.size(); ++i) {
    while (j < clean.size() && clean.points[j] != sub.points[i]) ++j;
    REQUIRE(j < clean.size());
    REQUIRE(sub.normals[i] == clean.normals[j]);
    ++j;
  }
  // Fewer points than count: all kept.
  CHECK(applied("subsample", "{count: 50000}", clean).points == clean.points);
}

TEST_CASE("corruptions are functions of their generator", "[datasets][corruptions]") {
  const PointCloud clean = sphere_points(5000);
  for (const auto& [type, yaml] : std::vector<std::pair<std::string, std::string>>{
           {"noise", "{sigma: 0.01}"}, {"holes", "{count: 3}"}, {"outliers", "{}"}, {"subsample", "{count: 100}"}}) {
    INFO(type);
    CHECK(applied(type, yaml, clean, 4).points == applied(type, yaml, clean, 4).points);
    CHECK(applied(type, yaml, clean, 4).points != applied(type, yaml, clean, 5).points);
  }
}

TEST_CASE("corruption options are checked, naming the field", "[datasets][corruptions][bad]") {
  CHECK_THROWS_WITH(make("noise", "{sigma: -1}"), "c.sigma: must be positive, got -1");
  CHECK_THROWS_WITH(make("noise", "{sigma: abc}"), Catch::StartsWith("c.sigma: expected a finite number"));
  CHECK_THROWS_WITH(make("noise", "{direction: up}"), Catch::StartsWith("c.direction: must be one of"));
  CHECK_THROWS_WITH(make("holes", "{radius: 0}"), "c.radius: must be positive, got 0");
  CHECK_THROWS_WITH(make("holes", "{count: 1.5}"), Catch::StartsWith("c.count: expected an integer"));
  CHECK_THROWS_WITH(make("plane_cut", "{normal: [0, 0, 0]}"), "c.normal: must be a non-zero vector");
  CHECK_THROWS_WITH(make("plane_cut", "{normal: [1, 0]}"), "c.normal: must have 3 entries, got 2");
  CHECK_THROWS_WITH(make("outliers", "{fraction: 2}"), "c.fraction: must be in (0, 1], got 2");
  CHECK_THROWS_WITH(make("subsample", "{count: 0}"), Catch::StartsWith("c.count: must be in [1, "));
  CHECK_THROWS_WITH(make("subsample", "{size: 10}"), Catch::StartsWith("c.size: unknown key"));
}
