#include "framework/pipeline/preset.hpp"

#include <yaml-cpp/yaml.h>

#include <map>

#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "framework/core/suggest.hpp"

namespace dtsl {

namespace {

std::map<std::string, std::vector<Preset>>& registered() {
  static std::map<std::string, std::vector<Preset>> presets;
  return presets;
}

}  // namespace

void register_preset(const std::string& type, Preset preset) {
  std::vector<Preset>& list = registered()[type];
  for (Preset& p : list)
    if (p.name == preset.name) {
      p = std::move(preset);
      return;
    }
  list.push_back(std::move(preset));
}

std::vector<Preset> presets(const std::string& type) {
  std::vector<Preset> out{{"default", "the pipeline's option defaults", {}}};
  const auto it = registered().find(type);
  if (it != registered().end())
    for (const Preset& p : it->second)
      if (p.name != "default") out.push_back(p);
  return out;
}

void apply_preset(Reconstructor& pipeline, const std::string& type, const std::string& name,
                  const std::string& context) {
  const std::vector<Preset> known = presets(type);
  std::vector<std::string> names;
  for (const Preset& p : known) {
    names.push_back(p.name);
    if (p.name != name) continue;
    // A preset that sets nothing (`default`) leaves the options as they are, unchecked: a pipeline
    // whose defaults are incomplete (`external` without its command) gets them after the preset.
    if (p.values.empty()) return;
    YAML::Node map(YAML::NodeType::Map);
    for (const PresetValue& v : p.values) {
      try {
        map[v.key] = YAML::Load(v.value);
      } catch (const YAML::Exception&) {
        throw ConfigError(context + ": preset '" + name + "' of pipeline '" + type + "': cannot parse " + v.key +
                          " = '" + v.value + "'");
      }
    }
    apply_yaml(pipeline.options(), map, context + " (preset '" + name + "')");
    return;
  }
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  throw ConfigError(context + ": unknown preset '" + name + "' of pipeline '" + type + "'" + did_you_mean(name, names) +
                    "; known: " + list + " (see `dtsl list preset`)");
}

}  // namespace dtsl
