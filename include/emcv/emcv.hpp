// SPDX-License-Identifier: MIT
/// \file
/// emcv — streaming estimators for real-time Monte Carlo subsurface control variates (Xie & Olano 2021).
/// Umbrella header: every public name of the library.
#pragma once

#include "version.hpp"
#include "weighted_covariance.hpp"
#include "running_covariance.hpp"
#include "emcm.hpp"
#include "ewma_covariance.hpp"
#include "moving_stats.hpp"
#include "control_variate.hpp"
#include "batch_means.hpp"
#include "sample_count.hpp"
// The adaptive-sampling policy is built on the GLM-based port (one source of truth with the shaders): it joins
// the umbrella where GLM is on the include path, and the rest of the API keeps needing only the standard library.
#if defined(__has_include)
#if __has_include(<glm/glm.hpp>)
#include "adaptive_sampling.hpp"
#endif
#endif

/// \namespace emcv
/// The C++ API: streaming covariance estimators, control variates and sample counts, templated on the
/// scalar type; docs/estimators.md.
