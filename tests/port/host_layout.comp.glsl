// SPDX-License-Identifier: MIT
// The port's structs in std430 storage buffers, one per struct that crosses a buffer (the renderer's passes,
// shaders/adaptive/budget_block.h, and an engine's per-pixel states): test_host_layout.cpp compiles it with
// glslang and compares spirv-cross's reflection of these blocks with emcv/port/host.hpp's offsetof and sizeof.
#version 450 core
#extension GL_GOOGLE_include_directive : require
#include "emcv/port/bindings.h"
#include "emcv/port/budget.h"
#include "emcv/port/ema.h"

layout(local_size_x = 1) in;

layout(std430, EMCV_LAYOUT_BINDING(0)) buffer Emcm2Buffer { EmcvEmcm2 emcm2[]; };
layout(std430, EMCV_LAYOUT_BINDING(1)) buffer MovingStatsBuffer { EmcvMovingStats moving_stats[]; };
layout(std430, EMCV_LAYOUT_BINDING(2)) buffer BudgetBuffer { EmcvBudgetBlock budget; };

void main() {
    emcm2[0].count = 1u;
    moving_stats[0].count = 1u;
    budget.solves = 1u;
}
