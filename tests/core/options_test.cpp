// Options structs read from YAML, --set overrides and the registry: errors name the key and the rule.
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "framework/config/options.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/config/yaml_path.hpp"
#include "framework/core/error.hpp"
#include "framework/core/types.hpp"
#include "framework/registry/registry.hpp"

using namespace dtsl;

namespace {

struct ExampleOptions final : Options {
  int depth = 8;
  double weight = 4.0;
  bool manifold = true;
  std::string mode = "fast";
  std::vector<double> axis = {0, 0, 1};
  void visit(FieldVisitor& v) override {
    v.field("depth", depth, "octree depth");
    v.field("weight", weight, "a weight");
    v.field("manifold", manifold, "a flag");
    v.field("mode", mode, "a choice");
    v.field("axis", axis, "a vector");
  }
  void check() const override {
    check_range("depth", depth, 1, 12);
    check_positive("weight", weight);
    check_one_of("mode", mode, {"fast", "slow"});
    require(axis.size() == 3, "axis", "must have 3 entries");
  }
};

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("apply_yaml sets fields and keeps defaults") {
  ExampleOptions o;
  apply_yaml(o, YAML::Load("{depth: 5, mode: slow, axis: [1, 0, 0]}"), "p");
  CHECK(o.depth == 5);
  CHECK(o.mode == "slow");
  CHECK(o.axis == std::vector<double>{1, 0, 0});
  CHECK(o.weight == 4.0);
  CHECK(to_json(o)["depth"] == 5);
  CHECK(describe(o).size() == 5);
}

TEST_CASE("apply_yaml errors name the key path and the rule") {
  ExampleOptions o;  // a failed apply leaves it half-set; each case below starts from a fresh one
  CHECK_THAT(message_of([&] { o = ExampleOptions(); apply_yaml(o, YAML::Load("{dpeth: 5}"), "pipelines[0].options"); }),
             Catch::Contains("pipelines[0].options.dpeth") && Catch::Contains("unknown key") &&
                 Catch::Contains("depth"));
  CHECK_THAT(message_of([&] { o = ExampleOptions(); apply_yaml(o, YAML::Load("{depth: deep}"), "x"); }),
             Catch::Contains("x.depth") && Catch::Contains("integer"));
  CHECK_THAT(message_of([&] { o = ExampleOptions(); apply_yaml(o, YAML::Load("{depth: 2.5}"), "x"); }), Catch::Contains("x.depth"));
  CHECK_THAT(message_of([&] { o = ExampleOptions(); apply_yaml(o, YAML::Load("{depth: 40}"), "x"); }),
             Catch::Contains("x.depth") && Catch::Contains("[1, 12]") && Catch::Contains("40"));
  CHECK_THAT(message_of([&] { o = ExampleOptions(); apply_yaml(o, YAML::Load("{weight: .nan}"), "x"); }), Catch::Contains("x.weight"));
  CHECK_THAT(message_of([&] { o = ExampleOptions(); apply_yaml(o, YAML::Load("{mode: medium}"), "x"); }),
             Catch::Contains("x.mode") && Catch::Contains("fast, slow"));
  CHECK_THAT(message_of([&] { o = ExampleOptions(); apply_yaml(o, YAML::Load("{manifold: 3}"), "x"); }), Catch::Contains("x.manifold"));
  CHECK_THAT(message_of([&] { o = ExampleOptions(); apply_yaml(o, YAML::Load("[1, 2]"), "x"); }), Catch::Contains("expected a map"));
  CHECK_THAT(message_of([&] { o = ExampleOptions(); apply_yaml(o, YAML::Load("{depth: }"), "x"); }), Catch::Contains("x.depth"));
}

TEST_CASE("apply_assignment parses textual values like YAML") {
  ExampleOptions o;
  apply_assignment(o, "axis", "[0, 1, 0]", "--set");
  CHECK(o.axis == std::vector<double>{0, 1, 0});
  apply_assignment(o, "depth", "3", "--set");
  CHECK(o.depth == 3);
  CHECK_THAT(message_of([&] { apply_assignment(o, "axis", "[1, 2]", "--set"); }), Catch::Contains("axis"));
}

TEST_CASE("set_yaml_path addresses map keys, list indices and named list entries") {
  YAML::Node doc = YAML::Load("{pipelines: [{name: a, options: {depth: 1}}, {name: b}], seed: 1}");
  set_yaml_path(doc, "pipelines.a.options.depth", YAML::Node(7));
  set_yaml_path(doc, "pipelines[1].options.depth", YAML::Node(9));
  set_yaml_path(doc, "seed", YAML::Node(5));
  CHECK(doc["pipelines"][0]["options"]["depth"].as<int>() == 7);
  CHECK(doc["pipelines"][1]["options"]["depth"].as<int>() == 9);
  CHECK(doc["seed"].as<int>() == 5);
  CHECK_THROWS_AS(set_yaml_path(doc, "pipelines.zzz.options.depth", YAML::Node(1)), ConfigError);
  CHECK_THROWS_AS(set_yaml_path(doc, "pipelines[5].name", YAML::Node(1)), ConfigError);
  CHECK_THROWS_AS(set_yaml_path(doc, "seed.x", YAML::Node(1)), ConfigError);
  CHECK_THROWS_AS(split_assignment("novalue"), ConfigError);
}

namespace {
struct Thing {
  ExampleOptions opts;
  Options& options() { return opts; }
};
}  // namespace

TEST_CASE("registry creates by name and lists known names on a miss") {
  Registry<Thing> r("thing");
  r.add("one", "the first", [] { return std::make_unique<Thing>(); });
  CHECK(r.create("one", "ctx"));
  CHECK_THROWS_AS(r.add("one", "again", [] { return std::make_unique<Thing>(); }), Error);
  CHECK_THAT(message_of([&] { r.create("two", "pipelines[3].type"); }),
             Catch::Contains("pipelines[3].type") && Catch::Contains("'two'") && Catch::Contains("one"));
  REQUIRE(r.listings().size() == 1);
  CHECK(describe(*r.listings()[0].default_options()).size() == 5);
}

TEST_CASE("unit cube normalisation maps the box to [-1,1]^3 with longest side 2") {
  std::vector<Vec3> pts = {{1, 2, 3}, {5, 2, 4}, {3, 3, 3}};
  const Similarity s = unit_cube_normalisation(pts, "pts");
  BoundingBox b;
  for (const Vec3& p : pts) b.extend(s.apply(p));
  CHECK(b.extent().maxCoeff() == Approx(2.0));
  CHECK(b.center().norm() == Approx(0.0).margin(1e-12));
  CHECK((s.invert(s.apply(pts[1])) - pts[1]).norm() < 1e-12);
  CHECK_THROWS_AS(unit_cube_normalisation({{1, 1, 1}, {1, 1, 1}}, "same"), AlgorithmError);
  CHECK_THROWS_AS(unit_cube_normalisation({}, "none"), AlgorithmError);
}
