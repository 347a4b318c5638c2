// SPDX-License-Identifier: MIT
// shaders/render/tiles.h — the SSS tile list and the sample statistics (compute passes only).
#ifndef EMCV_RENDER_TILES_H
#define EMCV_RENDER_TILES_H

#include "render/frame.h"

layout(std430, EMCV_LAYOUT_BINDING(EMCV_RENDER_STATS)) buffer Stats {
    EmcvStatsBlock stats;
};

layout(std430, EMCV_LAYOUT_BINDING(EMCV_RENDER_TILES)) buffer Tiles {
    uvec4 dispatch;  // xyz: glDispatchComputeIndirect arguments (emcv_render_classify_tile), w: tile count
    uint tiles[];    // tile x | tile y << 16
} tile_list;

/// The pixel a thread of an SSS-tile workgroup shades (8x8 threads per tile); (-1, -1), off screen, for the
/// workgroups of the last dispatch row past the tile count.
ivec2 emcv_render_tile_pixel() {
    uint index = gl_WorkGroupID.x + gl_WorkGroupID.y * uint(EMCV_RENDER_TILE_ROW);
    if (index >= tile_list.dispatch.w) return ivec2(-1);
    uint t = tile_list.tiles[index];
    return ivec2(int(t & 0xFFFFu), int(t >> 16u)) * EMCV_RENDER_TILE_SIZE + ivec2(gl_LocalInvocationID.xy);
}

shared uint emcv_render_tile_sss_pixels;

/// SSS tile classification (docs/frame.md), by the full-screen pass that already reads every pixel's material
/// (lighting), one 8x8 workgroup per tile: a tile holding a scattering pixel is appended to the tile list, and
/// the indirect dispatch arguments of the SSS passes (rows of EMCV_RENDER_TILE_ROW workgroups) grow with it by
/// atomic maxima, so no pass of its own and no one-thread dispatch writes them. Also counts the SSS pixels
/// (frame_stats.sss_pixels). The renderer resets the list's header to (0, 0, 1, 0) before the pass. Called by
/// every thread of the workgroup (it has barriers).
void emcv_render_classify_tile(bool scatters) {
    if (gl_LocalInvocationIndex == 0u) emcv_render_tile_sss_pixels = 0u;
    barrier();
    if (scatters) atomicAdd(emcv_render_tile_sss_pixels, 1u);
    barrier();
    if (gl_LocalInvocationIndex == 0u && emcv_render_tile_sss_pixels > 0u) {
        uint slot = atomicAdd(tile_list.dispatch.w, 1u);
        tile_list.tiles[slot] = gl_WorkGroupID.x | (gl_WorkGroupID.y << 16u);
        atomicAdd(stats.sss_pixels, emcv_render_tile_sss_pixels);
        uint row = uint(EMCV_RENDER_TILE_ROW);
        atomicMax(tile_list.dispatch.x, min(slot + 1u, row));
        atomicMax(tile_list.dispatch.y, slot / row + 1u);
    }
}

#endif  // #ifndef EMCV_RENDER_TILES_H
