// SPDX-License-Identifier: MIT
// Budget mode, pass 3 of 4: each pixel's N from its block's plan and the solved lambda (emcv_adaptive_budget_count).
// An engine's sampling loop would take N samples here; this test stores N and the host samples.
#include "app.glsl"

layout(local_size_x = EMCV_ADAPTIVE_TILE_SIZE, local_size_y = EMCV_ADAPTIVE_TILE_SIZE) in;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (app_code(p) == 0u) return;
    imageStore(app_taken, p, uvec4(emcv_adaptive_budget_count(p, app_frame.x, app_frame.y)));
}
