// Checks that a shape source rejects options with a ConfigError whose message names the key (under the
// context "s") and starts with `message`.
#pragma once

#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <string>

#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "framework/datasets/dataset.hpp"

namespace dtsl::test {

inline void expect_shape_option_error(const std::string& type, const std::string& yaml, const std::string& message) {
  register_dataset_plugins();
  auto shape = shape_sources().create(type, "s");
  try {
    apply_yaml(shape->options(), YAML::Load(yaml), "s");
    FAIL("no ConfigError for " << type << " " << yaml);
  } catch (const ConfigError& e) {
    CHECK_THAT(e.what(), Catch::StartsWith(message));
  }
}

}  // namespace dtsl::test
