// SPDX-License-Identifier: MIT
// Budget mode, pass 4 of 4: the tile's history update after sampling (emcv_adaptive_update_tile), from each pixel's
// tracked f and G (here a texture the host filled) and the samples it took.
#define EMCV_ADAPTIVE_TILE_UPDATE 1
#include "app.glsl"

layout(binding = 9) uniform sampler2D app_tracked;  // (f, G) per pixel

layout(local_size_x = EMCV_ADAPTIVE_TILE_SIZE, local_size_y = EMCV_ADAPTIVE_TILE_SIZE) in;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    uint n = app_code(p) != 0u ? imageLoad(app_taken, p).x : 0u;
    vec2 fg = n > 0u ? texelFetch(app_tracked, p, 0).xy : vec2(0.0f);
    emcv_adaptive_update_tile(gl_LocalInvocationIndex, emcv_adaptive_tile_origin(p), fg.x, fg.y, n);
}
