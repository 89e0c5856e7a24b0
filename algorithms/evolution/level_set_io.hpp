// Writing out the level-set stage (docs/design.md §6: "every stage's output can be written
// out and pictured"): the level set through tspline_io (re-loadable bit-identically), the summary and
// per-iteration history as JSON, and the T-mesh as line geometry for figures (the paper's Fig. 1a).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "algorithms/evolution/evolution.hpp"

namespace dtsl {

/// The JSON of a result: summary plus "history" (one object per iteration) and "best_iteration".
nlohmann::json to_json(const LevelSetResult& result);

/// Writes <prefix>.tspline (the level set), <prefix>.json (to_json(result)) and <prefix>_tmesh.obj
/// (the T-mesh's edges as 'l' records). Each file is written atomically; FileError on failure.
void save_level_set(const LevelSetResult& result, const std::string& prefix);

struct LoadedLevelSet {
  TSpline level_set;
  nlohmann::json record;  ///< the JSON written next to it (empty object if that file is missing)
};

/// Reads <prefix>.tspline and, if present, <prefix>.json. FileError naming the file for anything
/// malformed.
LoadedLevelSet load_level_set(const std::string& prefix);

}  // namespace dtsl
