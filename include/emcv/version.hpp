// SPDX-License-Identifier: MIT
/// \file
/// emcv version: the single source of truth (CMake parses these three lines).
#pragma once

#define EMCV_VERSION_MAJOR 0  ///< incompatible API changes
#define EMCV_VERSION_MINOR 1  ///< compatible additions
#define EMCV_VERSION_PATCH 0  ///< fixes
