// SPDX-License-Identifier: MIT
// The adaptive-update pass for method spvg (body: shaders/adaptive/update.h).
#version 450 core
#define EMCV_ADAPTIVE_SPVG
#include "adaptive/update.h"
