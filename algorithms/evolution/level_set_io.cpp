#include "algorithms/evolution/level_set_io.hpp"

#include <fstream>

#include "algorithms/tspline/tspline_io.hpp"
#include "framework/core/atomic_file.hpp"
#include "framework/core/error.hpp"

namespace dtsl {

nlohmann::json to_json(const LevelSetResult& result) {
  nlohmann::json j = result.summary;
  j["best_iteration"] = result.best_iteration;
  j["stop_reason"] = result.stop_reason;
  nlohmann::json history = nlohmann::json::array();
  for (const IterationRecord& r : result.history) history.push_back(to_json(r));
  j["history"] = std::move(history);
  return j;
}

void save_level_set(const LevelSetResult& result, const std::string& prefix) {
  save_tspline(prefix + ".tspline", result.level_set);
  const std::string text = to_json(result).dump(1);
  write_file_atomically(prefix + ".json", [&](std::ostream& out) { out << text << "\n"; });
  write_tmesh_obj(prefix + "_tmesh.obj", result.level_set.tmesh());
}

LoadedLevelSet load_level_set(const std::string& prefix) {
  LoadedLevelSet loaded{load_tspline(prefix + ".tspline"), nlohmann::json::object()};
  std::ifstream in(prefix + ".json");
  if (in) {
    try {
      in >> loaded.record;
    } catch (const nlohmann::json::exception& e) {
      throw FileError(prefix + ".json", std::string("malformed JSON: ") + e.what());
    }
  }
  return loaded;
}

}  // namespace dtsl
