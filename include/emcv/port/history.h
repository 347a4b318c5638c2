// SPDX-License-Identifier: MIT
// emcv/port/history.h — the adaptive SSS methods' per-pixel history (spvg, cv, cv-notex) in the shared
// C++/GLSL dialect (fp32): what a history texel holds, when it may be reused, the per-sample variance it
// estimates and the sample count that variance asks for.
//
// ABOUT      docs/renderer.md documents each layout, the derivations and the choices:
//              spvg, cv-notex  one RGBA16F texel: (mean, per-sample comoment / emcv_history_variance_unit(),
//                              count, 0) of the tracked scalar (spvg: gamma-space luminance f; cv-notex: the
//                              residual f - G, alpha = 1). The variance is stored in a fixed unit so that it
//                              stays far above binary16's smallest normal (6.1e-5) whatever the target.
//              cv              RGBA32F (C_ff, C_fG, C_GG, count) + RG32F (mean_f, mean_G): the covariances stay
//                              fp32 because C_ff - C_fG^2 / C_GG cancels (binary16 covariances gave N = 0 on
//                              0.2% of flicker frames in the study); the means too, because G is an in-frame
//                              constant: a mean of G rounded to half makes a static G push G - half(G) every
//                              frame, a phantom C_GG and alpha (measured on `static`).
//            Per-sample variance (supp. Eq. 25-27): a frame's output is the mean of its N_t samples, so the
//            history pushes it as a batch of N_t (port/ema.h, *_push_batch) and its comoments estimate the
//            variance of one sample, not of the N-sample output: the count no longer feeds back into its own
//            input. The EMCM's steady-state bias 2 (1 - eta) / (2 - eta) is divided out
//            (emcv_history_unbias).
//            Two ways to turn it into counts, the same for every method:
//              quality target  N = ceil(sigma^2 / EMCV_HISTORY_TARGET), clamped to [N_MIN, N_MAX]: the output's
//                              variance lands on the target (SPVG's intent, calibrated);
//              budget          a mean of EMCV_HISTORY_SPP_BUDGET samples per SSS pixel, N proportional to sigma
//                              (port/budget.h), the allocation of least mean squared error.
//            The count saturates at EMCV_HISTORY_MAX_COUNT (exact in binary16). A texel that is not finite, has
//            a negative variance or count, is refused: the pixel restarts (never spreads NaN/Inf).
//            A history younger than two frames has no variance yet: it asks for N_MAX under a quality target
//            (as on a reset) and for the budget B itself under a budget (the uniform share: no information).
// USAGE      EmcvMovingStats s; bool ok = emcv_history_decode_stats(texel, s);
//            int n = emcv_history_count_quality(emcv_history_sigma2_moving(s, EMCV_HISTORY_ETA_MOVING), ...);
// REFERENCES Xie & Olano 2021 (section 4-5, supp. Eq. 21, 25-27); SPVG 2020 (eta 0.2, target 1e-4, N <= 64).
#ifndef EMCV_PORT_HISTORY_H
#define EMCV_PORT_HISTORY_H

#include "port.h"
#include "budget.h"
#include "cv.h"
#include "ema.h"
#include "samples.h"

EMCV_PORT_BEGIN

// Tunables: each may be set before this header is included (`#define NAME value`, or the renderer's
// `--define NAME=VALUE`, which demo/render/tunables.cpp validates against the ranges given here). None is
// tuned on a scene: docs/renderer.md says where each comes from.

/// Quality-target mode: the variance of a pixel's output (gamma-space luminance) the count aims at; SPVG's
/// 1e-4. Range: (0, 1].
#ifndef EMCV_HISTORY_TARGET
#define EMCV_HISTORY_TARGET 1.0e-4f
#endif
/// Budget mode when > 0: the mean samples per SSS pixel and frame, spent in proportion to sigma; 0 selects the
/// quality target. Range: [0, N_MAX].
#ifndef EMCV_HISTORY_SPP_BUDGET
#define EMCV_HISTORY_SPP_BUDGET 0.0f
#endif
/// The most samples a pixel takes in a frame (SPVG's 64). Range: [1, 1024] integer, >= N_MIN.
#ifndef EMCV_HISTORY_N_MAX
#define EMCV_HISTORY_N_MAX 64
#endif
/// The fewest samples a pixel whose kernel is wider than a pixel takes: 1, so that every such pixel's history
/// keeps seeing its noise (a pixel at 0 would push no sample and never learn it needs one).
/// Range: [1, N_MAX] integer.
#ifndef EMCV_HISTORY_N_MIN
#define EMCV_HISTORY_N_MIN 1
#endif
/// SPVG's moving mean/variance weight (spvg, cv-notex). Range: (0, 0.5].
#ifndef EMCV_HISTORY_ETA_MOVING
#define EMCV_HISTORY_ETA_MOVING 0.2f
#endif
/// The EMCM weight of cv: SPVG's 0.2 rather than the paper's 0.05. With the per-sample variance pooled over
/// 3x3 pixels (emcv_history_pool_sigma2), 1 / eta = 5 frames of 9 pixels estimate sigma to about 16% (for the
/// residual's kurtosis near 9), which costs an allocation proportional to sigma about 0.1 dB, while a memory
/// of 20 frames keeps a light change's old noise pattern for 20 frames (docs/renderer.md, "The memory").
/// Range: (0, 0.5].
#ifndef EMCV_HISTORY_ETA_EMCM
#define EMCV_HISTORY_ETA_EMCM 0.2f
#endif
/// Saturating frame count of a history texel, an integer exact in binary16. Range: [2, 2048] unsigned.
#ifndef EMCV_HISTORY_MAX_COUNT
#define EMCV_HISTORY_MAX_COUNT 1024u
#endif

/// The unit the RGBA16F texels store variances in (not a tunable: a storage scale, 1e-4 of a display
/// luminance squared, so that variances from 1e-8 to 6 stay normal binary16 numbers).
EMCV_FN float emcv_history_variance_unit() { return 1.0e-4f; }

/// Gamma-space luminance (Rec. 709 weights, gamma 1/2.2) of a linear colour: the scalar SPVG tracks.
/// `precise` and written out (not dot()): every shader that tracks this value must get the same bits, and a
/// compiler free to contract the sum into FMAs does it differently per shader (measured: 2 binary16 ulps of
/// the stored variance apart between the history update and a probe shader).
EMCV_FN float emcv_gamma_luminance(EMCV_IN(vec3) linear_rgb) {
    EMCV_PRECISE float y = 0.2126f * linear_rgb.x + 0.7152f * linear_rgb.y + 0.0722f * linear_rgb.z;
    return pow(max(y, 0.0f), 1.0f / 2.2f);
}

/// (mean, variance / unit, count, 0) -> moving stats. False (and s reset) when the texel is poisoned:
/// not finite, a negative variance, a negative or fractional count.
EMCV_FN bool emcv_history_decode_stats(EMCV_IN(vec4) texel, EMCV_OUT(EmcvMovingStats) s) {
    s = emcv_moving_stats_init();
    bool finite = emcv_is_finite(texel.x) && emcv_is_finite(texel.y) && emcv_is_finite(texel.z);
    if (!finite || texel.y < 0.0f || texel.z < 0.0f || texel.z != floor(texel.z)) return false;
    s.mean = texel.x;
    s.variance = texel.y * emcv_history_variance_unit();
    s.count = uint(texel.z);
    return true;
}

/// SPVG / cv-notex history texel: (mean, variance / emcv_history_variance_unit(), count capped at
/// EMCV_HISTORY_MAX_COUNT, 0), the inverse of emcv_history_decode_stats.
EMCV_FN vec4 emcv_history_encode_stats(EMCV_IN(EmcvMovingStats) s) {
    return vec4(s.mean, s.variance / emcv_history_variance_unit(), float(min(s.count, EMCV_HISTORY_MAX_COUNT)), 0.0f);
}

/// cov_count = (C_ff, C_fG, C_GG, count), means = (mean_f, mean_G) -> EMCM. False (and s reset) when poisoned:
/// not finite, a negative variance, a negative or fractional count. (A C_fG beyond sqrt(C_ff C_GG) is left to
/// emcv_cv_optimal_residual_variance, which clamps the residual variance at 0.)
EMCV_FN bool emcv_history_decode_emcm2(EMCV_IN(vec4) cov_count, EMCV_IN(vec2) means, EMCV_OUT(EmcvEmcm2) s) {
    s = emcv_emcm2_init();
    bool finite = emcv_is_finite(cov_count.x) && emcv_is_finite(cov_count.y) && emcv_is_finite(cov_count.z) &&
                  emcv_is_finite(cov_count.w) && emcv_is_finite(means.x) && emcv_is_finite(means.y);
    if (!finite || cov_count.x < 0.0f || cov_count.z < 0.0f || cov_count.w < 0.0f ||
        cov_count.w != floor(cov_count.w))
        return false;
    s.mean = means;
    s.cov = vec3(cov_count.x, cov_count.y, cov_count.z);
    s.count = uint(cov_count.w);
    return true;
}

/// cv history, first texture: (C_ff, C_fG, C_GG, count capped at EMCV_HISTORY_MAX_COUNT).
EMCV_FN vec4 emcv_history_encode_emcm2_cov(EMCV_IN(EmcvEmcm2) s) {
    return vec4(s.cov.x, s.cov.y, s.cov.z, float(min(s.count, EMCV_HISTORY_MAX_COUNT)));
}

/// cv history, second texture: the means (mu_f, mu_G).
EMCV_FN vec2 emcv_history_encode_emcm2_means(EMCV_IN(EmcvEmcm2) s) { return s.mean; }

/// Whether a previous frame's texel at linear depth `prev_depth` shows the surface expected there at
/// `expected_prev_depth`: within 5% of it (false for NaN). Every history that is reprojected uses it (the
/// adaptive history below, the temporal resolve's, emcv/port/resolve.h).
EMCV_FN bool emcv_history_same_depth(float prev_depth, float expected_prev_depth) {
    return abs(prev_depth - expected_prev_depth) <= 0.05f * expected_prev_depth;
}

/// Reprojection test (SPVG's reset on failed reprojection): the previous frame's pixel under the reprojected
/// position must show the same material, a linear depth within 5% of where this surface point was then, and a
/// normal within ~25 degrees. Off-screen positions are the caller's test.
EMCV_FN bool emcv_history_reusable(uint material, uint prev_material, float expected_prev_depth, float prev_depth,
                                   EMCV_IN(vec3) normal, EMCV_IN(vec3) prev_normal) {
    if (material == 0u || material != prev_material) return false;
    if (!emcv_history_same_depth(prev_depth, expected_prev_depth)) return false;
    return dot(normal, prev_normal) >= 0.9f;
}

/// r with F(r) = 0.997 for a Burley profile of shape distance d is 16.6 d (the radius demo/scene/footprint.hpp
/// reports: `far` keeps it under a pixel). Range: (0, 100].
#ifndef EMCV_HISTORY_FOOTPRINT_RADIUS_PER_D
#define EMCV_HISTORY_FOOTPRINT_RADIUS_PER_D 16.6f
#endif

/// A sub-pixel kernel: 99.7% of the widest channel's profile within one pixel of the centre. Its scattered value
/// is the pixel's own diffuse up to the profile's tail, so the control-variate methods take 0 samples there
/// whatever the history says (the residual variance is not exactly 0 there: the tail's samples land on the
/// neighbours, measured on `far`; docs/renderer.md).
EMCV_FN bool emcv_history_sub_pixel(float widest_d_mm, float pixels_per_mm) {
    return EMCV_HISTORY_FOOTPRINT_RADIUS_PER_D * widest_d_mm * pixels_per_mm < 1.0f;
}

/// The exponential history's bias: at steady state with a constant batch size the comoment's expectation is
/// 2 (1 - eta) / (2 - eta) of the per-sample variance (the weights' sum of squares, docs/renderer.md), so the
/// estimate is the comoment times (2 - eta) / (2 (1 - eta)). eta in (0, 0.5].
EMCV_FN float emcv_history_unbias(float eta) { return (2.0f - eta) / (2.0f * (1.0f - eta)); }

/// What a pixel's per-sample variance slot holds when it has none: no variance yet (fewer than two frames;
/// the pixel takes n_max under a quality target, B under a budget) ...
EMCV_FN float emcv_history_no_variance() { return -1.0f; }
/// ... or no samples at all (a sub-pixel kernel under a control-variate method).
EMCV_FN float emcv_history_no_samples() { return -2.0f; }

/// spvg, cv-notex: the per-sample variance of the tracked scalar, or emcv_history_no_variance() before two
/// frames.
EMCV_FN float emcv_history_sigma2_moving(EMCV_IN(EmcvMovingStats) s, float eta) {
    if (s.count < 2u) return emcv_history_no_variance();
    EMCV_PRECISE float v = s.variance * emcv_history_unbias(eta);
    return v;
}

/// cv: the per-sample variance of the residual f - alpha G at the EMCM's alpha, (C_ff - C_fG^2 / C_GG)
/// unbiased (Eq. 31 with supp. Eq. 25-27), or emcv_history_no_variance() before two frames.
EMCV_FN float emcv_history_sigma2_cv(EMCV_IN(EmcvEmcm2) s, float eta) {
    if (s.count < 2u) return emcv_history_no_variance();
    EMCV_PRECISE float v = emcv_cv_optimal_residual_variance_emcm2(s) * emcv_history_unbias(eta);
    return v;
}

/// The coefficient cv predicts f's change from G's with: C_fG / C_GG (Eq. 31) once G has varied, else, for a
/// history that has only seen a static G, Eq. 42's mu_f / mu_G (F independent of the light's intensity: a light
/// scaled by k scales f and G alike), 0 where G's mean is 0.
EMCV_FN float emcv_history_predicted_alpha(EMCV_IN(EmcvEmcm2) s) {
    if (s.cov.z > emcv_float_min_normal()) return emcv_cv_coefficient_emcm2(s);
    return s.mean.y > emcv_float_min_normal() ? s.mean.x / s.mean.y : 0.0f;
}

/// A residual jump beyond 5 per-sample standard deviations is a change of the signal, not noise: by Chebyshev's
/// inequality noise of any distribution passes it at most 1 frame in 25 (a Gaussian once in 1.7 million).
EMCV_FN float emcv_history_change_z2() { return 25.0f; }

/// cv's update: f and G, the means of this frame's n samples, into the EMCM as a batch (supp. Eq. 21, 25-27).
/// Once the history is as old as its memory (1 / eta frames, so that sigma^2 is an estimate worth testing
/// against), a residual move e = (f - mu_f) - alpha (g - mu_G) with the predicted alpha beyond 5 sigma
/// (n e^2 > 25 sigma^2) is a change the control does not explain: it enters with the weight of a 5-sigma move
/// (n' = 25 sigma^2 / e^2), so a real rise of the noise still raises sigma^2 ((1 - eta)(1 + 25 eta unbias) per such
/// frame: 5.3x at eta 0.2),
/// and the means restart at (f, g), so that the frames after it are not read as noise for 1 / eta frames
/// (docs/renderer.md, "Changes the control does not explain"). Returns false when f or g is not finite.
EMCV_FN bool emcv_history_push_cv(EMCV_INOUT(EmcvEmcm2) s, float f, float g, float eta, float n) {
    float sigma2 = emcv_history_sigma2_cv(s, eta);
    bool mature = float(s.count) * eta >= 1.0f;
    if (mature && sigma2 > 0.0f && emcv_emcm2_valid(s) && emcv_is_finite(f) && emcv_is_finite(g)) {
        EMCV_PRECISE float e = (f - s.mean.x) - emcv_history_predicted_alpha(s) * (g - s.mean.y);
        EMCV_PRECISE float z2 = n * e * e;
        if (z2 > emcv_history_change_z2() * sigma2) {
            EMCV_PRECISE float weight = emcv_history_change_z2() * sigma2 / (e * e);
            emcv_emcm2_push_batch(s, vec2(f, g), eta, weight);
            s.mean = vec2(f, g);
            return true;
        }
    }
    return emcv_emcm2_push_batch(s, vec2(f, g), eta, n);
}

/// Pooling, one neighbour: adds a neighbour's per-sample variance to the running sum when it has one (codes
/// are skipped). Neighbours are visited row by row, dy then dx from -1 to 1, on the GPU and in C++.
EMCV_FN void emcv_history_pool_add(EMCV_INOUT(float) sum, EMCV_INOUT(uint) count, float sigma2) {
    if (!(sigma2 >= 0.0f)) return;
    sum = sum + sigma2;
    count = count + 1u;
}

/// The per-sample variance a pixel is allocated with: the mean over its 3x3 neighbours of the same material in
/// its 8x8 tile that have one (itself included), an unbiased estimate of the local variance with up to 9 times
/// less noise where the noise varies slowly across pixels (a Burley kernel wider than a pixel spreads each
/// light feature over its neighbours). A pixel whose own slot holds a code keeps the code.
EMCV_FN float emcv_history_pool_sigma2(float own, float sum, uint count) {
    if (!(own >= 0.0f) || count == 0u) return own;
    return sum / float(count);
}

/// Quality target: N = ceil(sigma2 / target) clamped to [n_min, n_max]; n_max without a variance or with a
/// NaN one; 0 for emcv_history_no_samples().
EMCV_FN int emcv_history_count_quality(float sigma2, float target, int n_min, int n_max) {
    if (sigma2 == emcv_history_no_samples()) return 0;
    if (sigma2 < 0.0f) return n_max;
    return emcv_sample_count(sigma2, target, n_min, n_max);
}

/// Budget: clamp(lambda sigma, n_min, n_max) rounded stochastically with u in [0, 1); the budget itself
/// (clamped to n_max) without a variance or with a NaN one; 0 for emcv_history_no_samples().
EMCV_FN int emcv_history_count_budget(float sigma2, float lambda, float budget, int n_min, int n_max, float u) {
    if (sigma2 == emcv_history_no_samples()) return 0;
    bool known = sigma2 >= 0.0f;  // false for no_variance and NaN
    float x = known ? emcv_budget_share(lambda, sqrt(sigma2), float(n_min), float(n_max)) : min(budget, float(n_max));
    return emcv_budget_round(x, u);
}

/// Whether the tunables select budget mode.
EMCV_FN bool emcv_history_budget_mode() { return EMCV_HISTORY_SPP_BUDGET > 0.0f; }

/// Quality-target mode's count under the tunables.
EMCV_FN int emcv_history_count_target(float sigma2) {
    return emcv_history_count_quality(sigma2, EMCV_HISTORY_TARGET, EMCV_HISTORY_N_MIN, EMCV_HISTORY_N_MAX);
}

/// Budget mode's count under the tunables.
EMCV_FN int emcv_history_count_spend(float sigma2, float lambda, float u) {
    return emcv_history_count_budget(sigma2, lambda, EMCV_HISTORY_SPP_BUDGET, EMCV_HISTORY_N_MIN, EMCV_HISTORY_N_MAX, u);
}

EMCV_PORT_END

#endif  // #ifndef EMCV_PORT_HISTORY_H
