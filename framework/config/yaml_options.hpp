// Generic reading and writing of Options structs: from a YAML map, from "key=value" overrides, to JSON,
// and as a human-readable listing. Unknown keys and wrong types are ConfigErrors naming the key path.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "framework/config/options.hpp"

namespace YAML {
class Node;
}

namespace dtsl {

/// Sets the fields of `options` from the YAML map `node`, then runs options.check(). `context` is the
/// key path of `node` (e.g. "pipelines[0].options") used as the prefix of every error message.
void apply_yaml(Options& options, const YAML::Node& node, const std::string& context);

/// Sets one field from its textual value (parsed as a YAML scalar or flow sequence), then check().
void apply_assignment(Options& options, const std::string& key, const std::string& value,
                      const std::string& context);

/// The fields and their current values.
nlohmann::json to_json(Options& options);

/// One line per field: name, type, default value, doc.
struct FieldDescription {
  std::string name, type, value, doc;
};
std::vector<FieldDescription> describe(Options& options);

}  // namespace dtsl
