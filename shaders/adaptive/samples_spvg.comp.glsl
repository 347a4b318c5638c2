// SPDX-License-Identifier: MIT
// The adaptive-samples pass for method spvg (body: shaders/adaptive/samples.h).
#version 450 core
#define EMCV_ADAPTIVE_SPVG
#include "adaptive/samples.h"
