#include "framework/config/yaml_path.hpp"

#include <yaml-cpp/yaml.h>

#include <vector>

#include "framework/core/error.hpp"

namespace dtsl {

namespace {

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : path) {
    if (c == '.' || c == '[' || c == ']') {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

bool is_index(const std::string& s) {
  return !s.empty() && s.size() < 9 && s.find_first_not_of("0123456789") == std::string::npos;
}

}  // namespace

void set_yaml_path(YAML::Node& root, const std::string& path, const YAML::Node& value) {
  const std::vector<std::string> segments = split_path(path);
  if (segments.empty()) throw ConfigError("--set: empty key");
  YAML::Node node = root;
  std::string walked;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const std::string& seg = segments[i];
    const bool last = i + 1 == segments.size();
    const std::string here = walked.empty() ? seg : walked + "." + seg;
    if (node.IsSequence()) {
      YAML::Node next;
      bool found = false;
      if (is_index(seg)) {
        const std::size_t k = std::stoul(seg);
        if (k >= node.size())
          throw ConfigError(here + ": index out of range (the list has " + std::to_string(node.size()) + " entries)");
        next = node[k];
        found = true;
      } else {
        for (std::size_t k = 0; k < node.size(); ++k)
          if (node[k].IsMap() && node[k]["name"] && node[k]["name"].Scalar() == seg) {
            next = node[k];
            found = true;
          }
        if (!found) throw ConfigError(here + ": no entry named '" + seg + "' in '" + walked + "'");
      }
      if (last) throw ConfigError(here + ": cannot replace a whole list entry; set one of its keys");
      node.reset(next);
    } else if (node.IsMap() || node.IsNull() || !node.IsDefined()) {
      if (last) {
        node[seg] = value;
        return;
      }
      YAML::Node next = node[seg];
      if (!next.IsDefined() || next.IsNull()) {
        node[seg] = YAML::Node(YAML::NodeType::Map);
        next = node[seg];
      }
      node.reset(next);
    } else {
      throw ConfigError(here + ": '" + walked + "' is a value, not a map or list");
    }
    walked = here;
  }
}

std::pair<std::string, std::string> split_assignment(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ConfigError("--set '" + text + "': expected key=value");
  return {text.substr(0, eq), text.substr(eq + 1)};
}

}  // namespace dtsl
