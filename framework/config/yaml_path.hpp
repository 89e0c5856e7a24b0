// Addressing a value inside a YAML document by a dotted path, for `--set key=value` overrides and
// sweeps. A segment is a map key, a list index ("datasets[2]" or "datasets.2"), or, in a list of maps,
// the entry whose `name` equals the segment ("pipelines.poisson.options.depth").
#pragma once

#include <string>

namespace YAML {
class Node;
}

namespace dtsl {

/// Sets the value at `path` in `root` (creating missing map keys in the last map), with `value` parsed
/// as YAML (so "8" is a number, "[0,0,1]" a list). ConfigError naming the path if a segment does not
/// resolve.
void set_yaml_path(YAML::Node& root, const std::string& path, const YAML::Node& value);

/// Parses "key=value" into its two parts; ConfigError if there is no '='.
std::pair<std::string, std::string> split_assignment(const std::string& text);

}  // namespace dtsl
