// dtsl list [KIND]: every registered plugin with its options, defaults and docs.
#include <algorithm>
#include <iomanip>
#include <iostream>

#include "experiments/cli.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/registry/registry.hpp"
#include "framework/pipeline/tables.hpp"

namespace dtsl::cli {

int list_command(Args& args) {
  const std::vector<std::string> rest = args.positionals();
  if (rest.size() > 1) throw UsageError{"list: expected at most one KIND"};
  bool any = false;
  std::string kinds;
  for (const RegistryBase* r : RegistryBase::all()) {
    kinds += (kinds.empty() ? "" : ", ") + r->kind();
    if (!rest.empty() && rest[0] != r->kind()) continue;
    any = true;
    std::cout << "== " << r->kind() << "s ==\n";
    for (const auto& l : r->listings()) {
      std::cout << "\n" << l.name << " — " << l.summary << "\n";
      auto opts = l.default_options();
      const std::vector<FieldDescription> fields = describe(*opts);
      // Columns as wide as this plugin's longest entry plus a space (long option names of the
      // pipelines must not run into their type).
      std::size_t name_w = 0, type_w = 0, value_w = 0;
      for (const FieldDescription& f : fields) {
        name_w = std::max(name_w, f.name.size() + 1);
        type_w = std::max(type_w, f.type.size() + 1);
        value_w = std::max(value_w, f.value.size() + 1);
      }
      for (const FieldDescription& f : fields)
        std::cout << "    " << std::left << std::setw(int(name_w)) << f.name << std::setw(int(type_w)) << f.type
                  << std::setw(int(value_w)) << f.value << f.doc << "\n";
    }
    std::cout << "\n";
  }
  if (!rest.empty() && !any) throw UsageError{"list: unknown kind '" + rest[0] + "'; known: " + kinds};
  if (rest.empty()) std::cout << "== table columns ==\n" << describe_columns() << "\n";
  return 0;
}

}  // namespace dtsl::cli
