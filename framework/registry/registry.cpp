#include "framework/registry/registry.hpp"

namespace dtsl {

std::vector<const RegistryBase*>& RegistryBase::all() {
  static std::vector<const RegistryBase*> registries;
  return registries;
}

}  // namespace dtsl
