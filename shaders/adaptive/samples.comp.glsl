// SPDX-License-Identifier: MIT
// shaders/adaptive/samples.comp.glsl — the adaptive-samples pass of every adaptive method in budget mode (the
// renderer defines the method's EMCV_ADAPTIVE_* from its row of the method table): over the SSS tiles, each block of
// K x K pixels (EMCV_HISTORY_BLOCK) reprojects last frame's history into this frame's and pools its per-sample
// variance over its tile
// (adaptive/samples.h), shrinks it towards the previous frame's mean (emcv_history_shrink_sigma2) and writes it
// (as its bits) for the burley pass, added to the histogram from which the solve pass after it solves lambda
// before the burley pass computes N (emcv/port/budget.h, adaptive/budget_block.h, adaptive/budget_solve.comp.glsl).
// Under a quality target N needs only the pixel's tile, so the method's burley program plans it itself
// and this pass is not recorded; built with a quality target (tests), it writes N.
#version 450 core

#include "adaptive/samples.h"

layout(local_size_x = EMCV_RENDER_TILE_SIZE, local_size_y = EMCV_RENDER_TILE_SIZE) in;

void main() {
    ivec2 p = emcv_render_tile_pixel();
    emcv_adaptive_share_pixel_of(p);
    EmcvAdaptiveBlock blk;
    float own, frames;
    emcv_adaptive_tile_sigma2(emcv_adaptive_tile_origin(p), blk, own, frames);
    if (emcv_adaptive_holds_block()) {
        uint j = gl_LocalInvocationIndex;
        if (blk.code != 0u) emcv_adaptive_allocate(j, blk, own);
    }
}
