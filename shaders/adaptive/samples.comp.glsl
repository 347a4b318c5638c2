// SPDX-License-Identifier: MIT
// shaders/adaptive/samples.comp.glsl — the adaptive-samples pass of every adaptive method in budget mode (the
// renderer defines the method's EMCV_ADAPTIVE_* from its row of the method table): over the SSS tiles, each SSS
// pixel reprojects last frame's history into this frame's and pools its per-sample variance over its tile
// (adaptive/samples.h), shrinks it towards the previous frame's mean (emcv_history_shrink_sigma2) and writes it
// (as its bits) for the burley pass, added to the histogram from which the pass's last workgroup solves lambda
// before the burley pass computes N (emcv/port/budget.h, adaptive/budget_block.h): one pass, no solve dispatch of
// its own. Under a quality target N needs only the pixel's tile, so the method's burley program plans it itself
// and this pass is not recorded; built with a quality target (tests), it writes N.
#version 450 core

#define EMCV_BUDGET_GROUP_THREADS (EMCV_RENDER_TILE_SIZE * EMCV_RENDER_TILE_SIZE)
#include "adaptive/samples.h"

layout(local_size_x = EMCV_RENDER_TILE_SIZE, local_size_y = EMCV_RENDER_TILE_SIZE) in;

void main() {
    uint here = gl_LocalInvocationIndex;
    if (emcv_history_budget_mode()) emcv_budget_group_clear(here);  // ordered before any add by the barrier below
    ivec2 p = emcv_render_tile_pixel();
    uint code;
    float frames;
    float own = emcv_adaptive_tile_sigma2(p, code, frames);
    if (code != 0u) emcv_adaptive_allocate(p, ivec2(gl_LocalInvocationID.xy), own, code);
    // Budget mode: every workgroup (those past the tile count too) reports; the last one solves lambda.
    if (emcv_history_budget_mode()) emcv_budget_finish_group(here, gl_NumWorkGroups.x * gl_NumWorkGroups.y);
}
