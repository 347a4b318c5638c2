// SPDX-License-Identifier: MIT
// shaders/render/tiles.h — the SSS tile list and the sample statistics (compute passes only).
#ifndef EMCV_RENDER_TILES_H
#define EMCV_RENDER_TILES_H

#include "render/frame.h"

layout(std430, EMCV_LAYOUT_BINDING(EMCV_RENDER_STATS)) buffer Stats {
    EmcvStatsBlock stats;
};

layout(std430, EMCV_LAYOUT_BINDING(EMCV_RENDER_TILES)) buffer Tiles {
    uvec4 dispatch;  // xyz: glDispatchComputeIndirect arguments (sss_dispatch.comp.glsl), w: tile count
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

#endif  // #ifndef EMCV_RENDER_TILES_H
