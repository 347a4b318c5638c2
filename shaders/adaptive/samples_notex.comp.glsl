// SPDX-License-Identifier: MIT
// The adaptive-samples pass for method cv-notex (body: shaders/adaptive/samples.h).
#version 450 core
#define EMCV_ADAPTIVE_NOTEX
#include "adaptive/samples.h"
