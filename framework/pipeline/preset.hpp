// Presets: named sets of option values of one pipeline, applied before a config's or the command
// line's own options. Every pipeline has `default` (its options' defaults: the best method the suite
// supports); a pipeline registers more where a published variant exists (`dtsl`'s `paper`: the method
// as published, each value citing the paper's section). An experiment names the preset of each
// pipeline entry (`preset:`), `dtsl reconstruct` takes `--preset`, and the Python module `preset=`,
// so "dtsl" means one method everywhere and a config states only what its experiment varies.
#pragma once

#include <string>
#include <vector>

#include "framework/pipeline/reconstructor.hpp"

namespace dtsl {

/// One option value of a preset and where it comes from (the paper's section, or why it differs).
struct PresetValue {
  std::string key;    ///< the option's name, as in `dtsl list pipeline TYPE`
  std::string value;  ///< as it would be written after --set KEY=
  std::string source;
};

struct Preset {
  std::string name;
  std::string description;
  std::vector<PresetValue> values;  ///< empty for `default`
};

/// Adds `preset` to the presets of pipeline `type` (replacing one of the same name). The values are
/// checked when the preset is applied (every registered preset goes through the tests).
void register_preset(const std::string& type, Preset preset);

/// The presets of pipeline `type`: `default` first, then the registered ones in order of registration.
std::vector<Preset> presets(const std::string& type);

/// Sets `pipeline`'s options to preset `name` of pipeline `type`. ConfigError naming `context`, the
/// unknown preset (with the known ones and a "did you mean"), or the preset's value that the options
/// reject.
void apply_preset(Reconstructor& pipeline, const std::string& type, const std::string& name,
                  const std::string& context);

}  // namespace dtsl
