// SPDX-License-Identifier: MIT
// shaders/render/tiles.h — the SSS tile list and the sample statistics (compute passes only).
#ifndef EMCV_RENDER_TILES_H
#define EMCV_RENDER_TILES_H

#include "render/frame.h"

layout(std430, EMCV_LAYOUT_BINDING(EMCV_RENDER_STATS)) buffer Stats {
    uint sss_pixels;
    uint sample_sum;
    uint sample_max;
    uint stats_unused;
} stats;

layout(std430, EMCV_LAYOUT_BINDING(EMCV_RENDER_TILES)) buffer Tiles {
    uvec4 dispatch;  // glDispatchComputeIndirect arguments (x = tile count, 1, 1) and unused
    uint tiles[];    // tile x | tile y << 16
} tile_list;

/// The pixel a thread of an SSS-tile workgroup shades (8x8 threads per tile).
ivec2 emcv_render_tile_pixel() {
    uint t = tile_list.tiles[gl_WorkGroupID.x];
    return ivec2(int(t & 0xFFFFu), int(t >> 16u)) * EMCV_RENDER_TILE_SIZE + ivec2(gl_LocalInvocationID.xy);
}

#endif  // #ifndef EMCV_RENDER_TILES_H
