// SPDX-License-Identifier: MIT
// One thread: the tile count of sss_tiles.comp.glsl -> glDispatchComputeIndirect arguments, rows of
// EMCV_RENDER_TILE_ROW workgroups (emcv_render_tile_pixel maps them back to tiles).
#version 450 core

#include "render/tiles.h"

layout(local_size_x = 1) in;

void main() {
    uint count = tile_list.dispatch.w;
    uint row = uint(EMCV_RENDER_TILE_ROW);
    tile_list.dispatch.x = min(count, row);
    tile_list.dispatch.y = (count + row - 1u) / row;
    tile_list.dispatch.z = 1u;
}
