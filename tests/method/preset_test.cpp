// Presets (framework/pipeline/preset.hpp) of the `dtsl` pipeline: every registered preset applies, sets
// what it says, and is overridden by options given after it; bad names are clear errors. Every config
// under configs/ names the preset of each pipeline entry that has more than `default`.
#include <catch2/catch.hpp>
#include <yaml-cpp/yaml.h>

#include <filesystem>

#include "algorithms/method/dtsl_pipeline.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "framework/pipeline/preset.hpp"
#include "framework/pipeline/reconstructor.hpp"

using namespace dtsl;

TEST_CASE("every preset of every pipeline applies and sets its values", "[preset]") {
  register_dtsl_pipeline();
  for (const std::string& type : reconstructors().names()) {
    const std::vector<Preset> list = presets(type);
    REQUIRE(!list.empty());
    CHECK(list.front().name == "default");
    for (const Preset& p : list) {
      INFO(type << " preset " << p.name);
      auto pipeline = reconstructors().create(type, "test");
      REQUIRE_NOTHROW(apply_preset(*pipeline, type, p.name, "test"));
      const nlohmann::json options = to_json(pipeline->options());
      for (const PresetValue& v : p.values) {
        INFO(v.key);
        REQUIRE(options.contains(v.key));
        CHECK(!v.source.empty());
        const YAML::Node value = YAML::Load(v.value);
        // The option now holds the preset's value (compared through YAML, as it was parsed).
        auto fresh = reconstructors().create(type, "test");
        apply_assignment(fresh->options(), v.key, v.value, "test");
        CHECK(to_json(fresh->options())[v.key] == options[v.key]);
      }
    }
  }
}

TEST_CASE("paper differs from default and options override it", "[preset]") {
  register_dtsl_pipeline();
  auto pipeline = reconstructors().create("dtsl", "test");
  const nlohmann::json defaults = to_json(pipeline->options());
  apply_preset(*pipeline, "dtsl", "paper", "test");
  const nlohmann::json paper = to_json(pipeline->options());
  CHECK(paper["evolution_velocity"] == "paper");
  CHECK(defaults["evolution_velocity"] != "paper");
  CHECK(paper["evolution_fine_levels"] == 0);
  apply_assignment(pipeline->options(), "bilateral_max_iterations", "4", "test");
  CHECK(to_json(pipeline->options())["bilateral_max_iterations"] == 4);
  CHECK(to_json(pipeline->options())["evolution_velocity"] == "paper");
  // Back to default: every value as before.
  apply_preset(*pipeline, "dtsl", "default", "test");
  auto fresh = reconstructors().create("dtsl", "test");
  apply_preset(*fresh, "dtsl", "default", "test");
  CHECK(to_json(fresh->options()) == defaults);
}

TEST_CASE("an unknown preset is a clear error", "[preset]") {
  register_dtsl_pipeline();
  auto pipeline = reconstructors().create("dtsl", "test");
  try {
    apply_preset(*pipeline, "dtsl", "papr", "pipelines[0].preset");
    FAIL("no error");
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    CHECK(m.find("pipelines[0].preset") != std::string::npos);
    CHECK(m.find("unknown preset 'papr'") != std::string::npos);
    CHECK(m.find("'paper'") != std::string::npos);  // did you mean
    CHECK(m.find("known: default, paper") != std::string::npos);
  }
}

TEST_CASE("every config names the preset of its pipelines that have presets", "[preset]") {
  register_dtsl_pipeline();
  namespace fs = std::filesystem;
  int configs = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(DTSL_SOURCE_DIR) / "configs")) {
    if (entry.path().extension() != ".yaml") continue;
    ++configs;
    const YAML::Node root = YAML::LoadFile(entry.path().string());
    const YAML::Node pipelines = root["pipelines"];
    REQUIRE(pipelines.IsSequence());
    for (std::size_t i = 0; i < pipelines.size(); ++i) {
      const std::string type = pipelines[i]["type"].Scalar();
      if (!reconstructors().contains(type) || presets(type).size() < 2) continue;
      INFO(entry.path().filename().string() << " pipelines[" << i << "] (" << type << ")");
      CHECK(pipelines[i]["preset"].IsDefined());
    }
  }
  CHECK(configs > 10);
}
