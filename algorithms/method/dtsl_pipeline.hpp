// The paper's whole method as one pipeline named `dtsl`: Phase 1 T-spline level set (TL) ->
// polygonizer (MT, mesh MI) -> displacement mapping (D-Map, mesh MD) -> data-driven bilateral
// evolution (B-Evl, mesh MS); stage names and mesh labels as in the paper's Table 1.
#pragma once

namespace dtsl {
/// Adds `dtsl` to reconstructors() (and the stage plugins it needs to their registries). Idempotent.
void register_dtsl_pipeline();
}
