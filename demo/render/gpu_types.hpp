// SPDX-License-Identifier: MIT
// The renderer's GPU blocks on the host: the structs of shaders/render/blocks.h (one definition for C++ and
// GLSL), under the names the host code uses, with their sizes checked against the std140 / std430 layout.
#pragma once

#include "render/blocks.h"

namespace emcv::demo::gpu {

using frame_block = EmcvFrameBlock;
using light_block = EmcvLight;
using material_block = EmcvMaterial;
using object_block = EmcvObject;
using pass_block = EmcvPassBlock;
using stats_block = EmcvStatsBlock;

// vec4-aligned members only: the GPU layouts have no padding the C++ layout lacks.
static_assert(sizeof(frame_block) == 5 * 64 + 8 * 16, "frame_block: std140 size");
static_assert(sizeof(light_block) == 128, "light_block: std430 size");
static_assert(sizeof(material_block) == 64, "material_block: std430 size");
static_assert(sizeof(object_block) == 144, "object_block: std430 size");
static_assert(sizeof(pass_block) == 32, "pass_block: std140 size");
static_assert(sizeof(stats_block) == 16, "stats_block: std430 size");

}  // namespace emcv::demo::gpu
