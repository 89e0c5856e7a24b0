#include "framework/pipeline/reconstructor.hpp"

namespace dtsl {

Registry<Reconstructor>& reconstructors() {
  static Registry<Reconstructor> registry("pipeline");
  return registry;
}

}  // namespace dtsl
