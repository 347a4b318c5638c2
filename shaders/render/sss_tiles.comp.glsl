// SPDX-License-Identifier: MIT
// SSS tile classification (docs/frame.md): one workgroup per 8x8 tile of the screen; a tile holding a scattering
// pixel is appended to the tile list (its count in the list's header; sss_dispatch.comp.glsl then writes the
// indirect dispatch arguments of the SSS passes, which so run over SSS tiles only). Also counts the SSS
// pixels (frame_stats.sss_pixels).
#version 450 core

#include "render/gbuffer_read.h"
#include "render/tiles.h"

layout(local_size_x = EMCV_RENDER_TILE_SIZE, local_size_y = EMCV_RENDER_TILE_SIZE) in;

shared uint tile_sss_pixels;

void main() {
    if (gl_LocalInvocationIndex == 0u) tile_sss_pixels = 0u;
    barrier();
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (emcv_render_on_screen(p) && emcv_render_scatters(emcv_render_material_code(p))) {
        atomicAdd(tile_sss_pixels, 1u);
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && tile_sss_pixels > 0u) {
        uint slot = atomicAdd(tile_list.dispatch.w, 1u);
        tile_list.tiles[slot] = gl_WorkGroupID.x | (gl_WorkGroupID.y << 16u);
        atomicAdd(stats.sss_pixels, tile_sss_pixels);
    }
}
