// SPDX-License-Identifier: MIT
// emcv version: the single source of truth (CMake parses these three lines).
#pragma once

#define EMCV_VERSION_MAJOR 0
#define EMCV_VERSION_MINOR 1
#define EMCV_VERSION_PATCH 0
