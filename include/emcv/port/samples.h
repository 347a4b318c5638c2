// SPDX-License-Identifier: MIT
/// \file
/// emcv/port/samples.h — adaptive sample count (SPVG 2020) in the shared C++/GLSL dialect (fp32).
//
// ABOUT      Float twin of emcv::sample_count (include/emcv/sample_count.hpp):
//                N = ceil(clamp(variance / target, n_min, n_max)),   NaN -> n_max
//            The arguments are not checked here (a shader cannot throw): the caller guarantees
//            target > 0 and 0 <= n_min <= n_max, which the C++ API enforces on the host side. Unchecked,
//            a target of 0 gives n_max (variance / 0 is +Inf or NaN). With EMCV_PORT_CHECKS 1 (port.h) a
//            violation returns -1 instead, a count no valid call returns.
// USAGE      int n = emcv_sample_count(var_r, 1e-4f, 8, 64);
#ifndef EMCV_PORT_SAMPLES_H
#define EMCV_PORT_SAMPLES_H

#include "port.h"

EMCV_PORT_BEGIN

/// clamp(q, n_min, n_max) rounded up; NaN gives n_max (a broken history samples at full rate).
EMCV_FN int emcv_clamp_count(float q, int n_min, int n_max) {
    if (emcv_is_nan(q) || q >= float(n_max)) return n_max;
    if (!(q > float(n_min))) return n_min;
    return int(ceil(q));
}

/// SPVG: N = clamp(variance / target, n_min, n_max), rounded up.
EMCV_FN int emcv_sample_count(float variance, float target, int n_min, int n_max) {
#if EMCV_PORT_CHECKS
    if (!EMCV_PORT_CHECK(emcv_is_finite(target) && target > 0.0f) || !EMCV_PORT_CHECK(n_min >= 0 && n_min <= n_max))
        return -1;
#endif
    return emcv_clamp_count(variance / target, n_min, n_max);
}

EMCV_PORT_END

#endif  // #ifndef EMCV_PORT_SAMPLES_H
