#include "framework/pipeline/reconstructor.hpp"

#include <utility>

#include "framework/core/error.hpp"

namespace dtsl {

const StageRecord& stage(const ReconstructionResult& result, const std::string& name) {
  std::string names;
  for (const StageRecord& s : result.stages) {
    if (s.name == name) return s;
    names += (names.empty() ? "" : ", ") + s.name;
  }
  throw Error("no stage '" + name + "' in the result (stages: " + (names.empty() ? "none" : names) + ")");
}

StageRecord& stage(ReconstructionResult& result, const std::string& name) {
  return const_cast<StageRecord&>(stage(std::as_const(result), name));
}

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
