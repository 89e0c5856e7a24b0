// Dataset entries: parsing with errors that name the key path, and building — normalisation of points
// and ground truth together, determinism by seed, the description, and the failures a user can cause.
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>

#include "framework/core/error.hpp"
#include "framework/datasets/dataset.hpp"
#include "framework/io/io.hpp"

using namespace dtsl;
namespace fs = std::filesystem;

namespace {

DatasetSpec parse(const std::string& yaml, const std::string& context = "datasets[0]") {
  return parse_dataset(YAML::Load(yaml), context);
}

Dataset build(const std::string& yaml, std::uint64_t seed = 1) {
  DatasetSpec spec = parse(yaml);
  return build_dataset(spec, seed);
}

void check_normalised(const Dataset& d) {
  const BoundingBox box = bounding_box(d.points.points);
  CHECK(box.extent().maxCoeff() == Approx(2.0).epsilon(1e-12));
  CHECK(box.center().norm() < 1e-12);
  for (const Vec3& p : d.points.points) REQUIRE(p.cwiseAbs().maxCoeff() <= 1.0 + 1e-12);
}

/// A temporary folder removed at scope exit.
struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("dtsl_datasets_test_" + std::to_string(::getpid()) + "_" +
                                        std::to_string(reinterpret_cast<std::uintptr_t>(this)));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

/// Sets an environment variable for the scope, restoring the previous value.
struct ScopedEnv {
  std::string name;
  std::optional<std::string> old;
  ScopedEnv(std::string n, const std::string& value) : name(std::move(n)) {
    if (const char* v = std::getenv(name.c_str())) old = v;
    ::setenv(name.c_str(), value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old) ::setenv(name.c_str(), old->c_str(), 1);
    else ::unsetenv(name.c_str());
  }
};

}  // namespace

TEST_CASE("register_dataset_plugins is idempotent and registers every plugin", "[datasets]") {
  register_dataset_plugins();
  register_dataset_plugins();
  CHECK(shape_sources().names() ==
        std::vector<std::string>{"block", "cgal_model", "dumbbell", "file", "high_genus", "lattice", "pair",
                                 "plate_holes", "sphere", "torus", "two_spheres"});
  CHECK(samplers().names() == std::vector<std::string>{"area", "none", "vertices"});
  CHECK(corruptions().names() ==
        std::vector<std::string>{"holes", "noise", "outliers", "plane_cut", "subsample"});
}

TEST_CASE("parse_dataset: names, maps with type and options, defaults", "[datasets][parse]") {
  const DatasetSpec s = parse(R"(
name: torus_noisy
shape: {type: torus, R: 1, r: 0.3}
sampler: {type: area, count: 5000, density_ratio: 4, density_axis: radial}
corruptions:
  - {type: noise, sigma: 0.003}
  - holes
  - {type: plane_cut, normal: [0, 0, 1], offset: 0.5}
seed: 7
)");
  CHECK(s.name == "torus_noisy");
  CHECK(s.shape_type == "torus");
  CHECK(s.sampler_type == "area");
  REQUIRE(s.corruptions.size() == 3);
  CHECK(s.corruptions[0].first == "noise");
  CHECK(s.corruptions[1].first == "holes");
  CHECK(s.corruptions[2].first == "plane_cut");
  CHECK(s.seed_offset == 7);

  const DatasetSpec bare = parse("{name: s, shape: sphere}");
  CHECK(bare.sampler_type == "vertices");  // the paper's inputs are scan vertices
  CHECK(bare.corruptions.empty());
  CHECK(bare.seed_offset == 0);
  CHECK(parse("{name: f, shape: {type: file, points: x.xyz}}").sampler_type == "none");
}

TEST_CASE("parse_dataset: bad entries are ConfigErrors naming the key path", "[datasets][parse][bad]") {
  auto error = [](const std::string& yaml, const std::string& context = "datasets[0]") -> std::string {
    try {
      parse(yaml, context);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "(no ConfigError)";
  };
  // The example of the brief, exactly.
  CHECK(error("{name: a, shape: sphere, corruptions: [{type: noise}, {type: noise, sigma: -1}]}", "datasets[2]") ==
        "datasets[2].corruptions[1].sigma: must be positive, got -1");
  // Unknown keys, at every level.
  CHECK_THAT(error("{name: a, shape: sphere, noise: 1}"),
             Catch::StartsWith("datasets[0].noise: unknown key; known keys: name, shape, sampler, corruptions, seed"));
  CHECK_THAT(error("{name: a, shape: {type: sphere, radius: 1, colour: red}}"),
             Catch::StartsWith("datasets[0].shape.colour: unknown key"));
  CHECK_THAT(error("{name: a, shape: sphere, sampler: {type: area, cnt: 5}}"),
             Catch::StartsWith("datasets[0].sampler.cnt: unknown key"));
  CHECK_THAT(error("{name: a, shape: sphere, corruptions: [{type: holes, radius: 0.1, size: 2}]}"),
             Catch::StartsWith("datasets[0].corruptions[0].size: unknown key"));
  // Unknown plugin names, listing the known ones.
  CHECK(error("{name: a, shape: cube}") ==
        "datasets[0].shape: unknown shape 'cube'; known: block, cgal_model, dumbbell, file, high_genus, lattice, "
        "pair, plate_holes, sphere, torus, two_spheres");
  CHECK(error("{name: a, shape: {type: cube}}") ==
        "datasets[0].shape.type: unknown shape 'cube'; known: block, cgal_model, dumbbell, file, high_genus, "
        "lattice, pair, plate_holes, sphere, torus, two_spheres");
  CHECK(error("{name: a, shape: sphere, sampler: poisson}") ==
        "datasets[0].sampler: unknown sampler 'poisson'; known: area, none, vertices");
  CHECK(error("{name: a, shape: sphere, corruptions: [{type: blur}]}") ==
        "datasets[0].corruptions[0].type: unknown corruption 'blur'; known: holes, noise, outliers, plane_cut, "
        "subsample");
  // Wrong types.
  CHECK_THAT(error("{name: a, shape: sphere, corruptions: [{type: noise, sigma: big}]}"),
             Catch::StartsWith("datasets[0].corruptions[0].sigma: expected a finite number, got 'big'"));
  CHECK_THAT(error("{name: a, shape: {type: sphere, centre: 3}}"),
             Catch::StartsWith("datasets[0].shape.centre: must have 3 entries, got 1"));
  CHECK(error("{name: a, shape: sphere, corruptions: {type: noise}}") ==
        "datasets[0].corruptions: expected a list of corruptions, got a map");
  CHECK(error("{name: a, shape: sphere, seed: x}") == "datasets[0].seed: expected an integer, got 'x'");
  CHECK(error("{name: a, shape: sphere, seed: 1.5}") == "datasets[0].seed: expected an integer, got '1.5'");
  CHECK(error("{name: a, shape: [sphere]}") ==
        "datasets[0].shape: expected a shape name or a map with 'type' and options, got a list");
  CHECK(error("{name: [a], shape: sphere}") == "datasets[0].name: expected a string, got a list");
  CHECK(error("[1, 2]") == "datasets[0]: expected a map with name, shape, sampler, corruptions, seed; got a list");
  // Out of range.
  CHECK_THAT(error("{name: a, shape: {type: torus, R: 1, r: 2}}"),
             Catch::StartsWith("datasets[0].shape.r: must be smaller than R"));
  CHECK_THAT(error("{name: a, shape: sphere, sampler: {type: area, count: -5}}"),
             Catch::StartsWith("datasets[0].sampler.count: must be in [1, "));
  // Missing or malformed required keys.
  CHECK_THAT(error("{shape: sphere}"), Catch::StartsWith("datasets[0].name: missing"));
  CHECK_THAT(error("{name: a}"), Catch::StartsWith("datasets[0].shape: missing (one of: block, cgal_model"));
  CHECK_THAT(error("{name: a, shape: {radius: 2}}"), Catch::StartsWith("datasets[0].shape: missing 'type'"));
  CHECK_THAT(error("{name: 'a b', shape: sphere}"), Catch::StartsWith("datasets[0].name: must be 1-128 characters"));
  // A sampler that does not fit the shape.
  CHECK_THAT(error("{name: a, shape: sphere, sampler: none}"),
             Catch::StartsWith("datasets[0].sampler: 'none' passes on the shape's own points"));
  CHECK_THAT(error("{name: a, shape: {type: file, points: p.xyz}, sampler: area}"),
             Catch::StartsWith("datasets[0].sampler: shape 'file' supplies its own points"));
}

TEST_CASE("build_dataset: points in [-1,1]^3 with longest side 2, ground truth moved with them",
          "[datasets][build]") {
  // Vertices of a sphere placed far from the origin: the points are the ground truth's vertices, so
  // after the common normalisation they must still coincide exactly.
  const Dataset d = build("{name: s, shape: {type: sphere, radius: 30, centre: [100, 0, -50], subdivisions: 3}}");
  check_normalised(d);
  REQUIRE(d.ground_truth);
  REQUIRE(d.points.size() == d.ground_truth->vertices.size());
  for (std::size_t i = 0; i < d.points.size(); ++i) {
    REQUIRE((d.points.points[i] - d.ground_truth->vertices[i]).norm() < 1e-12);
    REQUIRE(std::abs(d.points.points[i].norm() - 1.0) < 1e-12);
    REQUIRE((d.points.normals[i] - d.points.points[i]).norm() < 1e-12);
  }

  // With noise and outliers the box is the points', not the shape's; the ground truth follows.
  const Dataset n = build(R"({name: n, shape: block, sampler: {type: area, count: 20000},
                              corruptions: [{type: noise, sigma: 0.01}, {type: outliers, fraction: 0.02, margin: 0.2}]})");
  check_normalised(n);
  REQUIRE(n.ground_truth);
  const BoundingBox gt = bounding_box(n.ground_truth->vertices);
  CHECK(gt.extent().maxCoeff() < 2.0);  // the outliers' margin made the points' box larger
  CHECK(gt.center().norm() < 0.1);
}

TEST_CASE("build_dataset: lengths are in the frame of the shape normalised into [-1,1]^3", "[datasets][build]") {
  // A sphere of radius 30 becomes radius 1 before corruption: a cut at offset 0.5 keeps 3/4 of its area.
  const Dataset d = build(R"({name: c, shape: {type: sphere, radius: 30}, sampler: {type: area, count: 40000},
                              corruptions: [{type: plane_cut, normal: [0, 0, 1], offset: 0.5}]})");
  CHECK(d.points.size() == Approx(30000).epsilon(0.02));
  CHECK(d.description["corruptions"][0]["points_before"] == 40000);
  CHECK(d.description["corruptions"][0]["points_after"] == d.points.size());
}

TEST_CASE("build_dataset: the same spec and seed give identical points", "[datasets][build]") {
  const std::string yaml = R"({name: t, shape: torus, sampler: {type: area, count: 3000, density_ratio: 5},
                               corruptions: [{type: holes, count: 3}, noise, {type: outliers, fraction: 0.05},
                                             {type: subsample, count: 2000}]})";
  DatasetSpec spec = parse(yaml);
  const Dataset a = build_dataset(spec, 42), b = build_dataset(spec, 42);
  const Dataset c = build(yaml, 42);  // a fresh parse too
  CHECK(a.points.size() == 2000);
  CHECK(a.points.points == b.points.points);
  CHECK(a.points.normals == b.points.normals);
  CHECK(a.points.points == c.points.points);
  CHECK(a.description == c.description);
  CHECK(build(yaml, 43).points.points != a.points.points);
  // The entry's seed is added to the experiment's.
  CHECK(build(yaml.substr(0, yaml.size() - 1) + ", seed: 1}", 42).points.points == build(yaml, 43).points.points);
}

TEST_CASE("build_dataset: a corruption's options do not move the other stages' random choices",
          "[datasets][build]") {
  auto centres = [](const std::string& sigma) {
    return build("{name: h, shape: sphere, sampler: {type: area, count: 5000}, corruptions: "
                 "[{type: noise, sigma: " + sigma + "}, {type: holes, count: 2}]}")
        .description["corruptions"][1]["report"]["centres"];
  };
  // The hole centres are points of the noisy cloud, so they move by the noise; their indices do not.
  const auto a = centres("0.001"), b = centres("0.002");
  REQUIRE(a.size() == 2);
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < 3; ++k) CHECK(std::abs(a[i][k].get<double>() - b[i][k].get<double>()) < 0.02);
}

TEST_CASE("build_dataset: the description records types, options, counts and seed", "[datasets][build]") {
  const Dataset d = build(R"({name: desc, shape: {type: torus, r: 0.25}, sampler: {type: area, count: 1000},
                              corruptions: [{type: subsample, count: 600}], seed: 3})", 10);
  const nlohmann::json& j = d.description;
  CHECK(j["name"] == "desc");
  CHECK(j["seed"] == 13);
  CHECK(j["experiment_seed"] == 10);
  CHECK(j["seed_offset"] == 3);
  CHECK(j["shape"]["type"] == "torus");
  CHECK(j["shape"]["options"]["r"] == 0.25);
  CHECK(j["shape"]["options"]["R"] == 1.0);
  CHECK(j["shape"]["exact"] == true);
  CHECK(j["shape"]["ground_truth"]["faces"] == 2 * 160 * 64);
  CHECK(j["sampler"]["type"] == "area");
  CHECK(j["sampler"]["options"]["count"] == 1000);
  CHECK(j["sampler"]["points"] == 1000);
  CHECK(j["corruptions"][0]["type"] == "subsample");
  CHECK(j["corruptions"][0]["options"]["count"] == 600);
  CHECK(j["points"] == 600);
  CHECK(j["normals"] == "ground_truth");
  CHECK(j["normalisation"]["points"]["scale"].get<double>() > 0);
}

TEST_CASE("build_dataset: no point left, non-finite or coincident points are AlgorithmErrors naming the dataset",
          "[datasets][build][bad]") {
  CHECK_THROWS_WITH(build("{name: gone, shape: sphere, corruptions: [{type: plane_cut, offset: -2}]}"),
                    "dataset 'gone': no point remains after corruption 'plane_cut' (corruptions[0]), which "
                    "removed all 10242");
  CHECK_THROWS_AS(build("{name: gone, shape: sphere, corruptions: [{type: plane_cut, offset: -2}]}"), AlgorithmError);

  // A shape source that yields a NaN, and one whose points all coincide.
  struct Bad final : ShapeSource {
    PointCloud cloud;
    NoOptions o;
    Options& options() override { return o; }
    bool supplies_points() const override { return true; }
    ShapeData load() override {
      ShapeData d;
      d.points = cloud;
      return d;
    }
  };
  auto spec_with = [](std::vector<Vec3> points) {
    DatasetSpec spec;
    spec.name = "bad";
    spec.shape_type = "test";
    auto shape = std::make_unique<Bad>();
    shape->cloud.points = std::move(points);
    spec.shape = std::move(shape);
    spec.sampler_type = "none";
    spec.sampler = samplers().create("none", "test");
    return spec;
  };
  DatasetSpec nan = spec_with({{0, 0, 0}, {1, std::nan(""), 0}});
  CHECK_THROWS_WITH(build_dataset(nan, 1), Catch::StartsWith("dataset 'bad'") && Catch::Contains("NaN"));
  CHECK_THROWS_AS(build_dataset(nan, 1), AlgorithmError);
  DatasetSpec same = spec_with({{1, 2, 3}, {1, 2, 3}});
  CHECK_THROWS_WITH(build_dataset(same, 1), Catch::StartsWith("dataset 'bad'") && Catch::Contains("coincide"));

}

TEST_CASE("file shape: points and ground truth from files, normalised together", "[datasets][build]") {
  TempDir dir;
  // A sphere of radius 2 at (3, 3, 3) as ground truth; its vertices as the point file, with normals.
  register_dataset_plugins();
  DatasetSpec sphere = parse("{name: s, shape: {type: sphere, radius: 2, centre: [3, 3, 3], subdivisions: 2}}");
  const ShapeData truth = sphere.shape->load();
  PointCloud pts;
  pts.points = truth.mesh->vertices;
  pts.normals = truth.mesh->normals;
  const std::string points_file = (dir.path / "points.ply").string();
  const std::string mesh_file = (dir.path / "truth.off").string();
  write_points(points_file, pts);
  write_mesh(mesh_file, *truth.mesh);

  const Dataset d = build("{name: f, shape: {type: file, points: '" + points_file + "', ground_truth: '" +
                          mesh_file + "'}, corruptions: [{type: subsample, count: 100}]}");
  check_normalised(d);
  REQUIRE(d.points.size() == 100);
  REQUIRE(d.points.has_normals());
  REQUIRE(d.ground_truth);
  CHECK(d.ground_truth->faces.size() == truth.mesh->faces.size());
  // Every point is still a vertex of the ground truth, in the common frame.
  for (const Vec3& p : d.points.points) {
    double nearest = 1e9;
    for (const Vec3& v : d.ground_truth->vertices) nearest = std::min(nearest, (p - v).norm());
    REQUIRE(nearest < 1e-9);
  }

  // Only a ground-truth mesh: a sampler draws from it.
  const Dataset g = build("{name: g, shape: {type: file, ground_truth: '" + mesh_file + "'}, sampler: area}");
  CHECK(g.points.size() == 20000);

  // A missing file is a FileError naming it.
  CHECK_THROWS_AS(build("{name: m, shape: {type: file, points: '" + (dir.path / "nope.xyz").string() + "'}}"),
                  FileError);
  CHECK_THROWS_WITH(build("{name: m, shape: {type: file, points: '" + (dir.path / "nope.xyz").string() + "'}}"),
                    Catch::Contains("nope.xyz"));
}

TEST_CASE("cgal_model: a model missing from the cache says to run scripts/fetch_data.sh", "[datasets][bad]") {
  TempDir dir;
  const ScopedEnv env("DTSL_DATA_DIR", dir.path.string());
  CHECK(data_cache_dir() == dir.path.string());
  CHECK_THROWS_AS(build("{name: m, shape: {type: cgal_model, model: fandisk}}"), FileError);
  CHECK_THROWS_WITH(build("{name: m, shape: {type: cgal_model, model: fandisk}}"),
                    Catch::Contains("cgal-demo/data/meshes/fandisk.off") && Catch::Contains("scripts/fetch_data.sh"));

  // A cache that exists but lacks the model lists the ones it has.
  fs::create_directories(dir.path / "cgal-demo/data/meshes");
  std::ofstream(dir.path / "cgal-demo/data/meshes/tiny.off") << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  CHECK_THROWS_WITH(build("{name: m, shape: {type: cgal_model, model: fandisk}}"),
                    Catch::Contains("no model 'fandisk'") && Catch::Contains("known: tiny"));
}

TEST_CASE("data_cache_dir: DTSL_DATA_DIR, else XDG_CACHE_HOME/dtsl, else ~/.cache/dtsl", "[datasets]") {
  const ScopedEnv data("DTSL_DATA_DIR", "");
  {
    const ScopedEnv xdg("XDG_CACHE_HOME", "/x/cache");
    CHECK(data_cache_dir() == "/x/cache/dtsl");
  }
  const ScopedEnv xdg("XDG_CACHE_HOME", "");
  const ScopedEnv home("HOME", "/home/someone");
  CHECK(data_cache_dir() == "/home/someone/.cache/dtsl");
}
