// SPDX-License-Identifier: MIT
// emcv/port/ema.h — exponential moving covariance (EMCM) of the pair (f, G) and the moving mean/variance of
// one scalar, in the shared C++/GLSL dialect (fp32).
//
// ABOUT      The float twin of emcv::emcm<T, 2> and emcv::moving_stats<T> (include/emcv/emcm.hpp,
//            moving_stats.hpp), step for step in the same order of operations:
//                d = x - mu,  mu' = mu + r d,  Cov' = (1 - r) (Cov + r d d^T)      supp. Eq. 17 / Eq. 21
//            with r = 1 for the first accepted sample (it seeds mu, Cov = 0) and r = eta afterwards.
//            Non-finite samples are refused: state unchanged, `rejected` + 1, the push returns false.
// USAGE C++  emcv::port::EmcvEmcm2 s = emcv::port::emcv_emcm2_init(); emcv_emcm2_push(s, glm::vec2(f, g), 0.05f);
// USAGE GLSL EmcvEmcm2 s = emcv_emcm2_init(); emcv_emcm2_push(s, vec2(f, g), 0.05f);
// REFERENCES Xie & Olano 2021, supp. Eq. 17, 21, 24; SPVG 2020 (moving mean/variance, eta = 0.2).
#ifndef EMCV_PORT_EMA_H
#define EMCV_PORT_EMA_H

#include "port.h"

EMCV_PORT_BEGIN

/// EMCM state of (f, G): mean = (mu_f, mu_G), cov = (C_ff, C_fG, C_GG) (packed upper triangle, as in C++).
struct EmcvEmcm2 {
    vec2 mean;
    vec3 cov;
    uint count;     ///< accepted samples
    uint rejected;  ///< refused non-finite samples
};

/// Moving mean and variance of one scalar (emcv::moving_stats).
struct EmcvMovingStats {
    float mean;
    float variance;
    uint count;
    uint rejected;
};

EMCV_FN EmcvEmcm2 emcv_emcm2_init() {
    EmcvEmcm2 s;
    s.mean = vec2(0.0f);
    s.cov = vec3(0.0f);
    s.count = 0u;
    s.rejected = 0u;
    return s;
}

/// Adds the pair x = (f, G) with weight eta in (0, 1] (supp. Eq. 21). Returns false when x is not finite.
EMCV_FN bool emcv_emcm2_push(EMCV_INOUT(EmcvEmcm2) s, EMCV_IN(vec2) x, float eta) {
    if (!emcv_is_finite(x.x) || !emcv_is_finite(x.y)) {
        s.rejected = s.rejected + 1u;
        return false;
    }
    float r = s.count == 0u ? 1.0f : eta;
    EMCV_PRECISE float d0 = x.x - s.mean.x;
    EMCV_PRECISE float d1 = x.y - s.mean.y;
    EMCV_PRECISE float m0 = s.mean.x + r * d0;
    EMCV_PRECISE float m1 = s.mean.y + r * d1;
    float keep = 1.0f - r;
    EMCV_PRECISE float c00 = keep * (s.cov.x + r * d0 * d0);  // (1 - r)(C + r d d^T), supp. Eq. 21
    EMCV_PRECISE float c01 = keep * (s.cov.y + r * d0 * d1);
    EMCV_PRECISE float c11 = keep * (s.cov.z + r * d1 * d1);
    s.mean = vec2(m0, m1);
    s.cov = vec3(c00, c01, c11);
    s.count = s.count + 1u;
    return true;
}

EMCV_FN EmcvMovingStats emcv_moving_stats_init() {
    EmcvMovingStats s;
    s.mean = 0.0f;
    s.variance = 0.0f;
    s.count = 0u;
    s.rejected = 0u;
    return s;
}

/// mu' = mu + r (x - mu), var' = (1 - r)(var + r (x - mu)^2); r = 1 on the first sample, eta afterwards.
EMCV_FN bool emcv_moving_stats_push(EMCV_INOUT(EmcvMovingStats) s, float x, float eta) {
    if (!emcv_is_finite(x)) {
        s.rejected = s.rejected + 1u;
        return false;
    }
    float r = s.count == 0u ? 1.0f : eta;
    EMCV_PRECISE float d = x - s.mean;
    EMCV_PRECISE float m = s.mean + r * d;
    float keep = 1.0f - r;
    EMCV_PRECISE float v = keep * (s.variance + r * d * d);
    s.mean = m;
    s.variance = v;
    s.count = s.count + 1u;
    return true;
}

EMCV_PORT_END

#endif  // #ifndef EMCV_PORT_EMA_H
