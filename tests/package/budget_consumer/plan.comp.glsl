// SPDX-License-Identifier: MIT
// Budget mode, pass 1 of 4: each 8x8 tile reprojects its histories, pools their variances, shrinks them and adds
// them to the frame's histogram (emcv_adaptive_plan.glsl).
#include "app.glsl"

layout(local_size_x = EMCV_ADAPTIVE_TILE_SIZE, local_size_y = EMCV_ADAPTIVE_TILE_SIZE) in;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    uint code = app_code(p);
    emcv_adaptive_share_pixel(gl_LocalInvocationIndex, code, code != 0u && app_sub_pixel(p));
    EmcvAdaptiveBlock blk;
    float own, frames;
    emcv_adaptive_tile_sigma2(emcv_adaptive_tile_origin(p), blk, own, frames);
    if (emcv_adaptive_holds_block() && blk.code != 0u) emcv_adaptive_allocate(gl_LocalInvocationIndex, blk, own);
}
