// SPDX-License-Identifier: MIT
// The consumer's per-pixel kernel, written once in the port's dialect: main.cpp compiles it as C++ (with the
// installed <emcv/port/*.h>) and appends its text to `#version 450 core` + the installed emcv_port.glsl for
// the GPU (the #ifdef __cplusplus block is skipped there). A stream of (f, G) per pixel from the port's hash,
// the control variate's coefficient from the EMCM (supp. Eq. 21, Eq. 31), the residual's moving variance and
// the next frame's sample count (SPVG), as in docs/integration.md's recipe.
#ifdef __cplusplus
#include <emcv/port/cv.h>
#include <emcv/port/ema.h>
#include <emcv/port/hash.h>
#include <emcv/port/samples.h>
using namespace emcv::port;
#define CONSUMER_FN inline
#else
#define CONSUMER_FN
#endif

/// Sample k of pixel p: G = u1, f = 2 G + s u2 with a noise s = 0.01 (p % 8) that the control does not explain:
/// exact floats from the hash, EMCV_PRECISE arithmetic.
CONSUMER_FN vec2 consumer_sample(uint pixel, uint k) {
    uint h = emcv_pcg(emcv_pcg(pixel) + k);
    float u1 = emcv_uint_to_unit_float(h);
    float u2 = emcv_uint_to_unit_float(emcv_pcg(h));
    EMCV_PRECISE float f = 2.0f * u1 + 0.01f * float(pixel % 8u) * u2;
    return vec2(f, u1);
}

/// `updates` frames of one pixel: push (f, G) into the EMCM, the residual at the previous alpha into the moving
/// stats, and plan the next count from the residual's variance.
CONSUMER_FN void consumer_pixel(uint pixel, uint updates, EMCV_OUT(EmcvEmcm2) cov, EMCV_OUT(EmcvMovingStats) res,
                                EMCV_OUT(int) count) {
    cov = emcv_emcm2_init();
    res = emcv_moving_stats_init();
    for (uint k = 0u; k < updates; ++k) {
        vec2 x = consumer_sample(pixel, k);
        float alpha = emcv_cv_coefficient_emcm2(cov);  // alpha_{t-1}
        emcv_moving_stats_push(res, emcv_cv_residual(x.x, alpha, x.y), 0.2f);
        emcv_emcm2_push(cov, x, 0.05f);
    }
    count = emcv_sample_count(res.variance, 1e-4f, 1, 64);
}
