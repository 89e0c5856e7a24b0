// dtsl list [KIND [NAME]]: the registered plugins, short by default; one plugin's options on demand.
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "experiments/cli.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/core/suggest.hpp"
#include "framework/pipeline/preset.hpp"
#include "framework/pipeline/reconstructor.hpp"
#include "framework/pipeline/tables.hpp"
#include "framework/registry/registry.hpp"

namespace dtsl::cli {

namespace {

constexpr std::size_t kWidth = 100;  ///< wrap column of the listing

std::string plural(const std::string& kind) {
  if (!kind.empty() && kind.back() == 'y') return kind.substr(0, kind.size() - 1) + "ies";
  return kind + "s";
}

/// `text` as lines of at most kWidth characters, the first after `first`, the others indented by `indent`.
std::string wrapped(const std::string& first, const std::string& text, std::size_t indent) {
  std::ostringstream out;
  std::istringstream words(text);
  std::string word, line = first;
  bool empty = true;
  while (words >> word) {
    if (!empty && line.size() + 1 + word.size() > kWidth) {
      out << line << "\n";
      line = std::string(indent, ' ');
      empty = true;
    }
    line += (empty ? "" : " ") + word;
    empty = false;
  }
  out << line << "\n";
  return out.str();
}

const RegistryBase* find_kind(const std::string& name) {
  std::vector<std::string> kinds;
  for (const RegistryBase* r : RegistryBase::all()) {
    if (name == r->kind() || name == plural(r->kind())) return r;
    kinds.push_back(r->kind());
  }
  std::string known;
  for (const std::string& k : kinds) known += (known.empty() ? "" : ", ") + k;
  kinds.push_back("columns");
  kinds.push_back("preset");
  throw UsageError{"list: unknown kind '" + name + "'" + did_you_mean(name, kinds) + "; known: " + known +
                   ", preset, columns"};
}

void list_kinds() {
  for (const RegistryBase* r : RegistryBase::all()) {
    std::string names;
    for (const auto& l : r->listings()) names += (names.empty() ? "" : ", ") + l.name;
    const std::string head = plural(r->kind()) + ":";
    std::cout << wrapped(head + std::string(std::max<std::size_t>(head.size() + 1, 16) - head.size(), ' '), names, 16);
  }
  std::string with_presets;
  for (const auto& l : reconstructors().listings())
    if (presets(l.name).size() > 1) {
      std::string names;
      for (const Preset& p : presets(l.name)) names += (names.empty() ? "" : ", ") + p.name;
      with_presets += (with_presets.empty() ? "" : "; ") + l.name + ": " + names;
    }
  std::cout << wrapped("presets:        ", with_presets + " (every pipeline has default)", 16);
  std::cout << "\n`dtsl list KIND` describes each plugin of a kind, `dtsl list KIND NAME` its options,\n"
               "`dtsl list preset NAME` a preset's values, `dtsl list columns` the table columns.\n";
}

void list_plugins(const RegistryBase& registry) {
  std::size_t name_w = 0;
  for (const auto& l : registry.listings()) name_w = std::max(name_w, l.name.size());
  for (const auto& l : registry.listings()) {
    auto opts = l.default_options();
    const std::size_t n = describe(*opts).size();
    const std::string head = "  " + l.name + std::string(name_w + 2 - l.name.size(), ' ');
    std::cout << wrapped(head, l.summary + (n ? " (" + std::to_string(n) + (n == 1 ? " option)" : " options)") : ""),
                         head.size());
  }
  std::cout << "\n`dtsl list " << registry.kind() << " NAME` shows a plugin's options.\n";
}

void list_options(const RegistryBase& registry, const std::string& name) {
  std::vector<std::string> names;
  for (const auto& l : registry.listings()) {
    names.push_back(l.name);
    if (l.name != name) continue;
    std::cout << wrapped(l.name + " (" + registry.kind() + "): ", l.summary, 4) << "\n";
    auto opts = l.default_options();
    const std::vector<FieldDescription> fields = describe(*opts);
    if (fields.empty()) std::cout << "  no options\n";
    for (const FieldDescription& f : fields) {
      std::cout << "  " << f.name << "  (" << f.type << ", default " << f.value << ")\n";
      std::cout << wrapped("      ", f.doc, 6);
    }
    return;
  }
  throw UsageError{"list: unknown " + registry.kind() + " '" + name + "'" + did_you_mean(name, names) +
                   " (`dtsl list " + registry.kind() + "` lists them)"};
}

/// The presets of every pipeline that has more than `default`.
void list_presets() {
  for (const auto& l : reconstructors().listings())
    for (const Preset& p : presets(l.name))
      if (presets(l.name).size() > 1)
        std::cout << wrapped("  " + l.name + " " + p.name + ": ",
                             p.description + " (" + std::to_string(p.values.size()) + " values)", 6);
  std::cout << "\nEvery pipeline has `default` (its options' defaults). `dtsl list preset NAME` shows a preset's "
               "values;\nselect one with `preset:` in a config's pipeline entry or `--preset` in `dtsl reconstruct`.\n";
}

void list_preset(const std::string& name) {
  std::vector<std::string> names;
  bool found = false;
  for (const auto& l : reconstructors().listings())
    for (const Preset& p : presets(l.name)) {
      names.push_back(p.name);
      if (p.name != name || (p.values.empty() && presets(l.name).size() == 1)) continue;
      found = true;
      std::cout << wrapped(l.name + " " + p.name + ": ", p.description, 4);
      if (p.values.empty()) std::cout << "  the defaults of `dtsl list pipeline " << l.name << "`\n";
      for (const PresetValue& v : p.values) std::cout << wrapped("  " + v.key + " = " + v.value + "  ", v.source, 6);
      std::cout << "\n";
    }
  if (!found)
    throw UsageError{"list: unknown preset '" + name + "'" + did_you_mean(name, names) + " (`dtsl list preset` lists them)"};
}

}  // namespace

int list_command(Args& args) {
  const std::vector<std::string> rest = args.positionals();
  if (rest.size() > 2) throw UsageError{"list: expected at most KIND and NAME"};
  if (rest.empty()) {
    list_kinds();
  } else if (rest[0] == "columns" || rest[0] == "column") {
    if (rest.size() > 1) throw UsageError{"list columns: takes no NAME"};
    std::cout << wrapped("", describe_columns(), 0);
  } else if (rest[0] == "preset" || rest[0] == "presets") {
    if (rest.size() == 1) list_presets();
    else list_preset(rest[1]);
  } else if (rest.size() == 1) {
    list_plugins(*find_kind(rest[0]));
  } else {
    list_options(*find_kind(rest[0]), rest[1]);
  }
  return 0;
}

}  // namespace dtsl::cli
