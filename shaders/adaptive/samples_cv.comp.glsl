// SPDX-License-Identifier: MIT
// The adaptive-samples pass for method cv (body: shaders/adaptive/samples.h).
#version 450 core
#define EMCV_ADAPTIVE_CV
#include "adaptive/samples.h"
