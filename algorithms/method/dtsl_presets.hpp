// The presets of the `dtsl` pipeline (framework/pipeline/preset.hpp): `default`, its option defaults
// (chosen on the topology suite's dev half, docs/experiments.md), and `paper`, the method as published.
#pragma once

namespace dtsl {
/// Registers `paper` for pipeline `dtsl`. Idempotent.
void register_dtsl_presets();
}
