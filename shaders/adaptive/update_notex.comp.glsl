// SPDX-License-Identifier: MIT
// The adaptive-update pass for method cv-notex (body: shaders/adaptive/update.h).
#version 450 core
#define EMCV_ADAPTIVE_NOTEX
#include "adaptive/update.h"
