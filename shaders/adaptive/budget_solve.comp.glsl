// SPDX-License-Identifier: MIT
// shaders/adaptive/budget_solve.comp.glsl — budget mode's solve: one workgroup, dispatched after the pass whose
// workgroups added their pixels to the frame's histogram (the samples pass, or the burley pass that plans the
// next frame), reads and clears that histogram, solves lambda for the burley pass that spends it and stores the
// next frame's shrinkage prior (adaptive/budget_block.h, emcv_budget_solve; emcv/port/budget.h). A dispatch of
// its own rather than the histogramming pass's last workgroup: no workgroup of that pass waits on an atomic
// counter or carries the solve's code, and a GPU pays one small dispatch after it instead.
#version 450 core

#define EMCV_BUDGET_GROUP_THREADS (EMCV_RENDER_TILE_SIZE * EMCV_RENDER_TILE_SIZE)
#include "render/bindings.h"
#include "adaptive/budget_block.h"

layout(local_size_x = EMCV_BUDGET_GROUP_THREADS) in;

void main() { emcv_budget_solve(gl_LocalInvocationIndex); }
