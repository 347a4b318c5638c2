// SPDX-License-Identifier: MIT
/// \file
/// emcv/port/ema.h — exponential moving covariance (EMCM) of the pair (f, G) and the moving mean/variance of
/// one scalar, in the shared C++/GLSL dialect (fp32).
//
// ABOUT      The float twin of emcv::emcm<T, 2> and emcv::moving_stats<T> (include/emcv/emcm.hpp,
//            moving_stats.hpp), step for step in the same order of operations:
//                d = x - mu,  mu' = mu + r d,  Cov' = Cov + r (((1 - r) d) d^T - Cov)   supp. Eq. 17 / Eq. 21
//            i.e. Cov' = (1 - r)(Cov + r d d^T), evaluated as include/emcv/weighted_covariance.hpp does
//            (detail::comoment_step, plain mean accuracy; an overflowing x - mu is clamped to +-FLT_MAX and
//            the comoments saturate at +-FLT_MAX, as there)
//            with r = 1 for the first accepted sample (it seeds mu, Cov = 0) and r = eta afterwards.
//            Non-finite samples are refused: state unchanged, `rejected` + 1, the push returns false.
//            A stored state the update cannot have produced (read back from a texture: a NaN or Inf mean or
//            covariance, a negative variance) is reseeded by the next finite sample as a first sample and
//            counted in `reseeded`, as emcv::moving_stats_update does for its per-pixel arrays.
// USAGE C++  emcv::port::EmcvEmcm2 s = emcv::port::emcv_emcm2_init(); emcv_emcm2_push(s, glm::vec2(f, g), 0.05f);
// USAGE GLSL EmcvEmcm2 s = emcv_emcm2_init(); emcv_emcm2_push(s, vec2(f, g), 0.05f);
// REFERENCES Xie & Olano 2021, supp. Eq. 17, 21, 24; SPVG 2020 (moving mean/variance, eta = 0.2).
#ifndef EMCV_PORT_EMA_H
#define EMCV_PORT_EMA_H

#include "port.h"

EMCV_PORT_BEGIN

/// EMCM state of (f, G): mean = (mu_f, mu_G), cov = (C_ff, C_fG, C_GG) (packed upper triangle, as in C++).
struct EmcvEmcm2 {
    vec2 mean;      ///< (mu_f, mu_G)
    vec3 cov;       ///< (C_ff, C_fG, C_GG)
    uint count;     ///< accepted samples
    uint rejected;  ///< refused non-finite samples
    uint reseeded;  ///< invalid stored states replaced by a first sample
};

/// Moving mean and variance of one scalar (emcv::moving_stats).
struct EmcvMovingStats {
    float mean;     ///< mu
    float variance; ///< var
    uint count;     ///< accepted samples
    uint rejected;  ///< refused non-finite samples
    uint reseeded;  ///< invalid stored states replaced by a first sample
};

/// An empty EMCM state (the first accepted sample seeds the mean).
EMCV_FN EmcvEmcm2 emcv_emcm2_init() {
    EmcvEmcm2 s;
    s.mean = vec2(0.0f);
    s.cov = vec3(0.0f);
    s.count = 0u;
    s.rejected = 0u;
    s.reseeded = 0u;
    return s;
}

/// True when the stored state is one the update can have produced: finite, both variances >= 0 (NaN fails).
EMCV_FN bool emcv_emcm2_valid(EMCV_IN(EmcvEmcm2) s) {
    return emcv_is_finite(s.mean.x) && emcv_is_finite(s.mean.y) && emcv_is_finite(s.cov.y) && s.cov.x >= 0.0f &&
           s.cov.x <= emcv_float_max() && s.cov.z >= 0.0f && s.cov.z <= emcv_float_max();
}

/// One coordinate of the mean update, as detail::comoment_step (plain accuracy) in weighted_covariance.hpp:
///     d = clamp(x - mu, -FLT_MAX, FLT_MAX),  mu' = clamp(mu + r d, -FLT_MAX, FLT_MAX)
/// (an x - mu that overflows, x and mu of opposite signs near the top of the range, is clamped so the mean
/// still moves towards x and stays finite; so is a sum that rounds past FLT_MAX). Returns d.
EMCV_FN float emcv_mean_step(EMCV_INOUT(float) mu, float x, float r) {
    EMCV_PRECISE float d = x - mu;
    d = clamp(d, -emcv_float_max(), emcv_float_max());
    EMCV_PRECISE float m = mu + r * d;
    mu = clamp(m, -emcv_float_max(), emcv_float_max());  // r near 1, x near max: mu + r d can round past max
    return d;
}

/// One comoment: c' = c + r ((outer d_i) d_j - c) with outer = 1 - r, saturated to +-FLT_MAX (never Inf).
/// Equal to (1 - r)(c + r d_i d_j), supp. Eq. 21, written as detail::comoment_step evaluates it.
/// A batch's outer = (1 - r) n exceeds 1, so outer d_i can overflow where d_i did not: it saturates too, so
/// that a d_j of 0 gives a cross comoment step of 0, not Inf * 0 = NaN (the identity on every finite value).
EMCV_FN float emcv_comoment_step(float c, float r, float outer, float di, float dj) {
    EMCV_PRECISE float scaled = outer * di;
    scaled = clamp(scaled, -emcv_float_max(), emcv_float_max());
    EMCV_PRECISE float cn = c + r * (scaled * dj - c);
    return clamp(cn, -emcv_float_max(), emcv_float_max());
}

/// Adds the pair x = (f, G), the mean of a batch of n samples, with weight eta in (0, 1]: the comoments grow by
/// n d d^T instead of d d^T (outer = (1 - r) n), so that they estimate the per-sample covariance whatever
/// n was (supp. Eq. 25-27: a mean of n samples has 1/n of the per-sample covariance; docs/renderer.md derives
/// the expectation). n = 1 is supp. Eq. 21 exactly, bit for bit. Returns false when x is not finite.
EMCV_FN bool emcv_emcm2_push_batch(EMCV_INOUT(EmcvEmcm2) s, EMCV_IN(vec2) x, float eta, float n) {
#if EMCV_PORT_CHECKS
    // a debug build refuses what the host should have refused (port.h, CHECKS); NaN fails both compares
    if (!EMCV_PORT_CHECK(eta > 0.0f && eta <= 1.0f) || !EMCV_PORT_CHECK(n >= 1.0f && n <= emcv_float_max())) {
        s.rejected = s.rejected + 1u;
        return false;
    }
#endif
    if (!emcv_is_finite(x.x) || !emcv_is_finite(x.y)) {
        s.rejected = s.rejected + 1u;
        return false;
    }
    if (s.count != 0u && !emcv_emcm2_valid(s)) {  // an invalid stored state: x becomes its first sample
        s.mean = x;
        s.cov = vec3(0.0f);
        s.count = 0u;
        s.reseeded = s.reseeded + 1u;
    }
    float r = s.count == 0u ? 1.0f : eta;  // the first sample seeds the mean, Cov = 0
    EMCV_PRECISE float outer = (1.0f - r) * n;
    float m0 = s.mean.x;
    float m1 = s.mean.y;
    float d0 = emcv_mean_step(m0, x.x, r);
    float d1 = emcv_mean_step(m1, x.y, r);
    s.mean = vec2(m0, m1);
    s.cov = vec3(emcv_comoment_step(s.cov.x, r, outer, d0, d0), emcv_comoment_step(s.cov.y, r, outer, d0, d1),
                 emcv_comoment_step(s.cov.z, r, outer, d1, d1));
    s.count = s.count + 1u;
    return true;
}

/// Adds the pair x = (f, G) with weight eta in (0, 1] (supp. Eq. 21). Returns false when x is not finite.
EMCV_FN bool emcv_emcm2_push(EMCV_INOUT(EmcvEmcm2) s, EMCV_IN(vec2) x, float eta) {
    return emcv_emcm2_push_batch(s, x, eta, 1.0f);
}

/// An empty moving mean/variance.
EMCV_FN EmcvMovingStats emcv_moving_stats_init() {
    EmcvMovingStats s;
    s.mean = 0.0f;
    s.variance = 0.0f;
    s.count = 0u;
    s.rejected = 0u;
    s.reseeded = 0u;
    return s;
}

/// True when the stored state is one the update can have produced: finite, variance >= 0 (NaN fails).
EMCV_FN bool emcv_moving_stats_valid(EMCV_IN(EmcvMovingStats) s) {
    return emcv_is_finite(s.mean) && s.variance >= 0.0f && s.variance <= emcv_float_max();
}

/// Adds x, the mean of a batch of n samples: mu' = mu + r (x - mu), var' = var + r (((1 - r) n d) d - var);
/// r = 1 on the first sample, eta afterwards. n = 1 is emcv::moving_stats (= emcm<T, 1>), same operations;
/// n scales the variance to a per-sample one as in emcv_emcm2_push_batch.
EMCV_FN bool emcv_moving_stats_push_batch(EMCV_INOUT(EmcvMovingStats) s, float x, float eta, float n) {
#if EMCV_PORT_CHECKS
    if (!EMCV_PORT_CHECK(eta > 0.0f && eta <= 1.0f) || !EMCV_PORT_CHECK(n >= 1.0f && n <= emcv_float_max())) {
        s.rejected = s.rejected + 1u;
        return false;
    }
#endif
    if (!emcv_is_finite(x)) {
        s.rejected = s.rejected + 1u;
        return false;
    }
    if (s.count != 0u && !emcv_moving_stats_valid(s)) {  // an invalid stored state: x becomes its first sample
        s.mean = x;
        s.variance = 0.0f;
        s.count = 0u;
        s.reseeded = s.reseeded + 1u;
    }
    float r = s.count == 0u ? 1.0f : eta;
    EMCV_PRECISE float outer = (1.0f - r) * n;
    float m = s.mean;
    float d = emcv_mean_step(m, x, r);
    s.mean = m;
    s.variance = emcv_comoment_step(s.variance, r, outer, d, d);
    s.count = s.count + 1u;
    return true;
}

/// mu' = mu + r (x - mu), var' = var + r (((1 - r) d) d - var); r = 1 on the first sample, eta afterwards
/// (emcv::moving_stats = emcm<T, 1>, same operations).
EMCV_FN bool emcv_moving_stats_push(EMCV_INOUT(EmcvMovingStats) s, float x, float eta) {
    return emcv_moving_stats_push_batch(s, x, eta, 1.0f);
}

EMCV_PORT_END

#endif  // #ifndef EMCV_PORT_EMA_H
