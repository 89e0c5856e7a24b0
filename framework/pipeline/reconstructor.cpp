#include "framework/pipeline/reconstructor.hpp"

namespace dtsl {

Registry<Reconstructor>& reconstructors() {
  static Registry<Reconstructor> registry("pipeline");
  return registry;
}

void transform(ReconstructionResult& result, const Similarity& s) {
  transform(result.mesh, s);
  for (StageRecord& stage : result.stages) {
    if (stage.mesh) transform(*stage.mesh, s);
    if (stage.lines)
      for (auto& segment : stage.lines->segments)
        for (Vec3& p : segment) p = s.apply(p);
  }
}

}  // namespace dtsl
