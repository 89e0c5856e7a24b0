// dtsl list [KIND]: every registered plugin with its options, defaults and docs.
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
      for (const FieldDescription& f : describe(*opts))
        std::cout << "    " << std::left << std::setw(26) << f.name << std::setw(8) << f.type << std::setw(14)
                  << f.value << f.doc << "\n";
    }
    std::cout << "\n";
  }
  if (!rest.empty() && !any) throw UsageError{"list: unknown kind '" + rest[0] + "'; known: " + kinds};
  if (rest.empty()) std::cout << "== table columns ==\n" << describe_columns() << "\n";
  return 0;
}

}  // namespace dtsl::cli
