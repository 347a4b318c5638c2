// SPDX-License-Identifier: MIT
// The adaptive-update pass for method cv (body: shaders/adaptive/update.h).
#version 450 core
#define EMCV_ADAPTIVE_CV
#include "adaptive/update.h"
