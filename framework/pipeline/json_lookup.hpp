// Reading run records (metrics.json): a nested value by its key path, and a number formatted for a
// table cell or a figure label. Shared by the tables and the report.
#pragma once

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>

namespace dtsl {

/// The value at j[path[0]][path[1]]..., or nullptr where a key is missing or a value is not an object.
inline const nlohmann::json* json_at(const nlohmann::json& j, std::initializer_list<const char*> path) {
  const nlohmann::json* cur = &j;
  for (const char* k : path) {
    if (!cur->is_object() || !cur->contains(k)) return nullptr;
    cur = &(*cur)[k];
  }
  return cur;
}

/// printf(format, value x scale), or "–" where there is no finite number.
inline std::string format_json_number(const nlohmann::json* v, double scale, const char* format) {
  if (!v || !v->is_number()) return "–";
  const double x = v->get<double>() * scale;
  if (!std::isfinite(x)) return "–";
  char buf[64];
  std::snprintf(buf, sizeof buf, format, x);
  return buf;
}

}  // namespace dtsl
