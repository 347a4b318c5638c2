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
//                              (port/budget.h), the allocation of least mean squared error, with each pooled
//                              sigma^2 first shrunk towards the previous frame's mean by the empirical-Bayes
//                              weight of its effective frames (emcv_history_shrink_sigma2).
//            The count saturates at EMCV_HISTORY_MAX_COUNT (exact in binary16). A texel that is not finite, has
//            a negative variance or count, is refused: the pixel restarts (never spreads NaN/Inf).
//            A history younger than two frames has no variance yet: it asks for N_MAX under a quality target
//            (as on a reset) and under a budget for the frame's mean variance (the uniform share: no
//            information), or B itself before any frame had a variance.
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

/// Budget mode: 1 lets the burley pass of a frame whose next frame shows the same view (and the same surfaces)
/// plan that frame's counts from the history it has just updated, as that frame's samples pass would, bit for bit:
/// the next frame then records no samples pass (docs/renderer.md, "Planning the next frame"). 0 always records
/// the samples pass. A renderer's choice of passes, not a formula: no function of the port reads it. Range: [0, 1].
#ifndef EMCV_HISTORY_PLAN_AHEAD
#define EMCV_HISTORY_PLAN_AHEAD 1
#endif
/// Budget mode with EMCV_HISTORY_PLAN_AHEAD: while the view and the lights stay still, the history is updated
/// (and the next frames planned) on one frame in M = EMCV_HISTORY_UPDATE_PERIOD; the frames between sample with
/// the counts that update planned and record nothing else. After a change of view or lights (and at the start)
/// every frame updates until a pixel gone dark has released its samples: max(1 / eta, 2 ln(B / N_MIN) /
/// -ln(1 - eta)) updates, 19 at B = 8 (docs/renderer.md, "Updating one frame in M"). 1 updates every frame. A renderer's choice of passes, not a formula: no function
/// of the port reads it. Range: [1, 16] integer.
#ifndef EMCV_HISTORY_UPDATE_PERIOD
#define EMCV_HISTORY_UPDATE_PERIOD 8
#endif

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
/// The grain of the statistics: one history texel, one per-sample variance and one N per K x K block of pixels
/// (K = EMCV_HISTORY_BLOCK), the block's f and G the means over its scattering pixels (emcv_history_block_batch).
/// K^2 times less history memory and per-pixel statistics work (reprojection, pooling, histograms, the EMCM
/// update); the allocation loses the variation of sigma within a block (docs/renderer.md, "Block statistics").
/// Range: 1, 2 or 4 (a divisor of the 8x8 SSS tile).
#ifndef EMCV_HISTORY_BLOCK
#define EMCV_HISTORY_BLOCK 1
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

/// A block's batch (EMCV_HISTORY_BLOCK): m scattering pixels that each took n samples, their per-pixel outputs f_i
/// of per-sample variances sigma_i^2 independent of each other (each pixel draws its own rotation), have the mean
/// f_b = (1/m) sum f_i of variance (1/m^2) sum sigma_i^2 / n = sbar^2 / (n m), sbar^2 = (1/m) sum sigma_i^2: the
/// block's mean is a batch mean of n m samples of the per-sample variance sbar^2 (supp. Eq. 25-27), so its history,
/// pushed with the batch n m, estimates sbar^2, the mean of its pixels' per-sample variances. That is what the
/// counts need: under a budget the blocks' error sum_b m_b sbar_b^2 / N_b at a total sum_b m_b N_b is smallest at
/// N_b proportional to sbar_b (the Neyman allocation of emcv/port/budget.h, each block weighted by its m_b pixels),
/// and under a quality target N_b = sbar_b^2 / target brings the block's pixels to the target on average.
EMCV_FN float emcv_history_block_batch(uint n, uint pixels) { return float(n * pixels); }

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

// Shrinkage of the pooled variance towards the frame's mean (budget mode; docs/renderer.md, "Shrinkage").
// An allocation proportional to a noisy sigma loses to the even split, and a history just restarted has a noisy
// sigma. Empirical Bayes: with the true sigma_i^2 spread across pixels with mean m and variance tau^2, and an
// estimate s2_i of sampling variance v_i, the posterior mean is w s2_i + (1 - w) m with w = tau^2 / (tau^2 + v_i).
// v_i = r E[sigma^4] / K_i: K_i effective frames of the pool (emcv_history_pool_frames), r the relative variance of
// one frame's term n d^2 (emcv_history_frame_relative_variance), E[sigma^4] = m^2 + tau^2 (the prior's, so that
// w does not depend on the noisy s2_i itself). m and tau^2 are the previous frame's, from the histogram of the
// pooled variances before shrinkage (emcv_history_frame_prior).

/// The residual's per-sample kurtosis the shrinkage assumes: 9.36, the median per pixel on `static` at 128x128
/// over 190 one-sample frames (docs/renderer.md, "Pooling"; a measurement, not a tunable).
EMCV_FN float emcv_history_residual_kurtosis() { return 9.36f; }

/// a^n for n < 2^11 by squaring (no pow(): the same bits in C++ and on every GPU).
EMCV_FN float emcv_history_power(float a, uint n) {
    EMCV_PRECISE float result = 1.0f;
    EMCV_PRECISE float base = a;
    for (uint k = 0u; k < 11u; ++k) {
        if ((n & (1u << k)) != 0u) result = result * base;
        base = base * base;
    }
    return result;
}

/// Effective frames of a history's per-sample variance: its count - 1 frame terms n d^2 (the first frame
/// only seeds the mean) carry the weights a^j, a = 1 - eta, and (sum w)^2 / sum w^2 =
/// (1 - a^n)(1 + a) / ((1 - a)(1 + a^n)) with n = count - 1 (capped at EMCV_HISTORY_MAX_COUNT): 1 at count 2,
/// (2 - eta) / eta at saturation (9 at eta 0.2). 0 before two frames (no variance yet).
EMCV_FN float emcv_history_effective_frames(uint count, float eta) {
    if (count < 2u) return 0.0f;
    float a = 1.0f - eta;
    float an = emcv_history_power(a, min(count, EMCV_HISTORY_MAX_COUNT) - 1u);
    EMCV_PRECISE float frames = (1.0f - an) * (1.0f + a) / (eta * (1.0f + an));
    return frames;
}

/// Relative variance Var(n d^2) / sigma^4 of one frame's term for a batch mean of n samples whose per-sample
/// kurtosis is `kurtosis`: the batch mean's kurtosis is 3 + (kurtosis - 3) / n, minus 1.
EMCV_FN float emcv_history_frame_relative_variance(float kurtosis, float n) {
    EMCV_PRECISE float r = 2.0f + (kurtosis - 3.0f) / n;
    return r;
}

/// The relative bias of a per-sample variance measured at the level mean_f when the level is now f (this frame's
/// mean of n samples): noise that follows its light scales its variance with the level squared (in display gamma
/// as in linear light), so the bias is E[f]^2 / mean_f^2 - 1, with E[f]^2 estimated without bias as
/// f^2 - sigma2 / n. At least -1 (the level gone), at most 1000 (a level from 0, where mean_f is not normal).
EMCV_FN float emcv_history_level_bias(float f, float mean_f, float sigma2, float n) {
    if (!(mean_f > emcv_float_min_normal())) return f > emcv_float_min_normal() ? 1000.0f : 0.0f;
    EMCV_PRECISE float level2 = max(f * f - sigma2 / n, 0.0f) / (mean_f * mean_f);
    return min(level2 - 1.0f, 1000.0f);
}

/// The effective frames of an estimate resting on `frames` frames and off by the relative bias `bias`: its
/// relative mean squared error is r / frames + bias^2 (r = emcv_history_frame_relative_variance, one frame's),
/// that of r / (r / frames + bias^2) frames. `frames` itself when frames is 0 or bias is 0.
EMCV_FN float emcv_history_biased_frames(float frames, float bias, float relative) {
    if (!(frames > 0.0f)) return frames;
    EMCV_PRECISE float inverse = 1.0f / frames + bias * bias / relative;
    return 1.0f / inverse;
}

/// The largest count, at least 2 (a history with a variance) and at most `count`, whose effective frames
/// (emcv_history_effective_frames, increasing in the count) are at most `frames`: bisection, pow-free (the same
/// bits in C++ and on every GPU). `count` itself when it is under 2 or its frames are within `frames`; a count
/// past EMCV_HISTORY_MAX_COUNT comes back at most at the cap.
EMCV_FN uint emcv_history_count_for_frames(uint count, float eta, float frames) {
    if (count < 2u || emcv_history_effective_frames(count, eta) <= frames) return count;
    uint lo = 2u;  // answer >= lo
    uint hi = min(count, EMCV_HISTORY_MAX_COUNT);  // frames(hi) > frames (the frames saturate at the cap)
    for (uint k = 0u; k < 11u && hi - lo > 1u; ++k) {
        uint mid = (lo + hi) / 2u;
        if (emcv_history_effective_frames(mid, eta) <= frames) lo = mid; else hi = mid;
    }
    return lo;
}

/// The change test of cv's and cv-notex's push: a residual move e of a frame of n samples beyond 5 sigma
/// (n e^2 > 25 sigma^2, Chebyshev's bound) is a change, not noise; true then, with `weight` the batch size it
/// enters with, that of a 5-sigma move (25 sigma^2 / e^2 < n). sigma^2 is the history's per-sample variance
/// (> 0, a history as old as its memory: the caller's test).
EMCV_FN bool emcv_history_change_weight(float e, float n, float sigma2, EMCV_OUT(float) weight) {
    EMCV_PRECISE float z2 = n * e * e;
    weight = n;
    if (!(z2 > emcv_history_change_z2() * sigma2)) return false;
    EMCV_PRECISE float clipped = emcv_history_change_z2() * sigma2 / (e * e);
    weight = clipped;
    return true;
}

/// cv's update: f and G, the means of this frame's n samples, into the EMCM as a batch (supp. Eq. 21, 25-27).
/// Once the history is as old as its memory (1 / eta frames, so that sigma^2 is an estimate worth testing
/// against), a residual move e = (f - mu_f) - alpha (g - mu_G) with the predicted alpha beyond 5 sigma
/// (n e^2 > 25 sigma^2) is a change the control does not explain: it enters with the weight of a 5-sigma move
/// (n' = 25 sigma^2 / e^2), so a real rise of the noise still raises sigma^2 ((1 - eta)(1 + 25 eta unbias) per such
/// frame: 5.3x at eta 0.2),
/// and the means restart at (f, g), so that the frames after it are not read as noise for 1 / eta frames
/// (docs/renderer.md, "Changes the control does not explain"). A change the control does explain still moves the
/// level: when f itself moves beyond 5 sigma in a history as old as its memory (n (f - mu_f)^2 > 25 sigma^2,
/// Chebyshev as above), the variance the history holds was measured at the old level and is off by the relative
/// bias emcv_history_level_bias; the count is lowered to the frames the estimate is then worth
/// (emcv_history_biased_frames, emcv_history_count_for_frames), which the budget's shrinkage weighs it by
/// (docs/renderer.md, "After a change: the stale allocation"). Returns false when f or g is not finite.
EMCV_FN bool emcv_history_push_cv(EMCV_INOUT(EmcvEmcm2) s, float f, float g, float eta, float n) {
    float sigma2 = emcv_history_sigma2_cv(s, eta);
    bool mature = float(s.count) * eta >= 1.0f;
    if (mature && sigma2 > 0.0f && emcv_emcm2_valid(s) && emcv_is_finite(f) && emcv_is_finite(g)) {
        EMCV_PRECISE float e = (f - s.mean.x) - emcv_history_predicted_alpha(s) * (g - s.mean.y);
        float weight;
        if (emcv_history_change_weight(e, n, sigma2, weight)) {
            emcv_emcm2_push_batch(s, vec2(f, g), eta, weight);
            s.mean = vec2(f, g);
            return true;
        }
    }
    float mean_f = s.mean.x;
    EMCV_PRECISE float level_move = f - mean_f;
    EMCV_PRECISE float level_z2 = n * level_move * level_move;
    bool pushed = emcv_emcm2_push_batch(s, vec2(f, g), eta, n);
    if (pushed && mature && sigma2 > 0.0f && level_z2 > emcv_history_change_z2() * sigma2) {
        float bias = emcv_history_level_bias(f, mean_f, sigma2, n);
        float relative = emcv_history_frame_relative_variance(emcv_history_residual_kurtosis(), n);
        float trusted = emcv_history_biased_frames(emcv_history_effective_frames(s.count, eta), bias, relative);
        s.count = emcv_history_count_for_frames(s.count, eta, trusted);
    }
    return pushed;
}

/// cv-notex's update: its residual r = f - G (alpha = 1; f and G the means of this frame's n samples) into the
/// moving mean/variance as a batch (supp. Eq. 25-27), with cv's change test at alpha = 1: once the history is as
/// old as its memory, a move e = r - mu_r beyond 5 sigma (n e^2 > 25 sigma^2, Chebyshev as in
/// emcv_history_push_cv) is a change that G does not explain: it enters with the weight of a 5-sigma move
/// (n' = 25 sigma^2 / e^2) and the mean restarts at r. Without it, a light change moves r wherever the scattered
/// light differs from the unscattered (a shadow edge the kernel reaches across), and that step stays in sigma^2 as
/// noise for many frames (it decays at 1 - eta a frame), so the budget spends there rather than where the noise
/// is (docs/renderer.md, "cv-notex and the change test"). Returns false when r is not finite.
EMCV_FN bool emcv_history_push_notex(EMCV_INOUT(EmcvMovingStats) s, float f, float g, float eta, float n) {
    float r = emcv_cv_residual(f, 1.0f, g);
    float sigma2 = emcv_history_sigma2_moving(s, eta);
    bool mature = float(s.count) * eta >= 1.0f;
    if (mature && sigma2 > 0.0f && emcv_moving_stats_valid(s) && emcv_is_finite(r)) {
        EMCV_PRECISE float e = r - s.mean;
        float weight;
        if (emcv_history_change_weight(e, n, sigma2, weight)) {
            emcv_moving_stats_push_batch(s, r, eta, weight);
            s.mean = r;
            return true;
        }
    }
    return emcv_moving_stats_push_batch(s, r, eta, n);
}

// The tile's noise test (docs/renderer.md, "After a change: the stale allocation"). A light change the control
// explains moves no residual, so the change test above does not fire, yet the noise may have changed: a pixel
// whose samples reached the lit surface of a light that went off keeps that light's variance for about 1 / eta
// frames while its own level hardly moves, and the budget keeps spending there. This frame's residual e
// against the history's prediction measures the noise now: n e^2 / sigma^2 has mean rho, the ratio of this
// frame's per-sample variance to the history's. One pixel's term is too noisy to act on (its relative variance
// is r, emcv_history_frame_relative_variance), so it is averaged over the scattering pixels of the pixel's 8x8
// tile that have one (the term is relative to each pixel's own variance, so pixels of different materials and
// levels measure the same ratio); where that mean says the noise fell, the history's comoments are scaled down by
// the estimated ratio (emcv_history_rescale_cv) instead of being forgotten at 1 - eta a frame.

/// The noise test, one pixel's term before its push: n e^2 / sigma^2 with e the residual move the change test
/// reads, capped at emcv_history_change_z2() (a move beyond it is a change, which the push clips to that
/// weight), or emcv_history_no_variance() for a history the change test does not read (younger than 1 / eta
/// frames, without a variance or not valid) or a non-finite f or g.
EMCV_FN float emcv_history_noise_term(EMCV_IN(EmcvEmcm2) s, float f, float g, float eta, float n) {
    float sigma2 = emcv_history_sigma2_cv(s, eta);
    bool mature = float(s.count) * eta >= 1.0f;
    if (!(mature && sigma2 > 0.0f && n > 0.0f && emcv_emcm2_valid(s) && emcv_is_finite(f) && emcv_is_finite(g)))
        return emcv_history_no_variance();
    EMCV_PRECISE float e = (f - s.mean.x) - emcv_history_predicted_alpha(s) * (g - s.mean.y);
    EMCV_PRECISE float z2 = n * e * e / sigma2;
    return min(z2, emcv_history_change_z2());
}

/// The relative variance of one pixel's noise-test term at its n: r = emcv_history_frame_relative_variance at the
/// residual's kurtosis (the shrinkage's r, at this frame's n).
EMCV_FN float emcv_history_noise_relative(float n) {
    return emcv_history_frame_relative_variance(emcv_history_residual_kurtosis(), n);
}

/// The noise test's pool sums in fixed point, units of 2^-16, so that a sum is exact and the same in any order (the
/// burley pass adds with shared-memory atomics, C++ in row order): a term is at most 25 and a relative variance at
/// most 2 + 6.36 (n >= 1), at most 1.7e6 units each; 64 pixels stay under 1.1e8 < 2^32. A unit is far under either
/// value's own noise.
EMCV_FN uint emcv_history_noise_units(float x) { return uint(x * 65536.0f + 0.5f); }

/// The noise test's pool, one pixel: adds its term and the term's relative variance (emcv_history_noise_relative),
/// in units (emcv_history_noise_units), and 1 to (sum of terms, sum of relative variances, pixels) when it has a
/// term.
EMCV_FN void emcv_history_noise_add(EMCV_INOUT(uvec3) pool, float term, float relative) {
    if (!(term >= 0.0f)) return;
    pool = uvec3(pool.x + emcv_history_noise_units(term), pool.y + emcv_history_noise_units(relative), pool.z + 1u);
}

/// The ratio a pool (emcv_history_noise_add) scales its pixels' comoments by: the mean term z estimates the
/// ratio rho of the noise now to the history's, with sampling variance v = (sum of r) / pixels^2 under no change;
/// the bias of the history is estimated without that noise, |rho - 1| = sqrt(max((z - 1)^2 - v, 0)) (the square of
/// a noisy estimate exceeds the true square by its variance), and only a fall is acted on: 1 - that, in (0, 1].
/// A rise is left to the change test, which clips it per pixel. 1 without terms.
EMCV_FN float emcv_history_noise_ratio(EMCV_IN(uvec3) pool) {
    if (pool.z == 0u) return 1.0f;
    float m = float(pool.z);
    EMCV_PRECISE float z = float(pool.x) * (1.0f / 65536.0f) / m;
    if (!(z < 1.0f)) return 1.0f;
    EMCV_PRECISE float v = float(pool.y) * (1.0f / 65536.0f) / (m * m);
    EMCV_PRECISE float bias2 = (z - 1.0f) * (z - 1.0f) - v;
    if (!(bias2 > 0.0f)) return 1.0f;
    return 1.0f - sqrt(bias2);
}

/// Scales cv's comoments by ratio (emcv_history_noise_ratio): the residual variance C_ff - C_fG^2 / C_GG scales
/// by it, the coefficient C_fG / C_GG and the means stay. A ratio of 1 (or not in (0, 1)) leaves the state as it
/// is, bit for bit.
EMCV_FN void emcv_history_rescale_cv(EMCV_INOUT(EmcvEmcm2) s, float ratio) {
    if (!(ratio > 0.0f && ratio < 1.0f)) return;
    s.cov = s.cov * ratio;
}

/// Pooling, one neighbour's effective frames: adds 1 / frames to the running sum when the neighbour has a
/// variance (the same neighbours as emcv_history_pool_add).
EMCV_FN void emcv_history_pool_add_frames(EMCV_INOUT(float) inverse_sum, float sigma2, float frames) {
    if (!(sigma2 >= 0.0f) || !(frames > 0.0f)) return;
    inverse_sum = inverse_sum + 1.0f / frames;
}

/// The effective frames of a pooled variance, the mean of `count` neighbours' estimates of K_j frames each:
/// its sampling variance is r sigma^4 sum_j (1 / K_j) / count^2, that of count^2 / sum (1 / K_j) frames.
/// 0 when no neighbour has a variance.
EMCV_FN float emcv_history_pool_frames(uint count, float inverse_sum) {
    if (count == 0u || !(inverse_sum > 0.0f)) return 0.0f;
    EMCV_PRECISE float frames = float(count) * float(count) / inverse_sum;
    return frames;
}

/// The empirical-Bayes weight tau^2 / (tau^2 + r (m^2 + tau^2) / frames) of an estimate resting on `frames`
/// effective frames: 0 without frames or without spread (tau^2 = 0: the spread is all noise, spend evenly),
/// towards 1 as frames grows.
EMCV_FN float emcv_history_shrink_weight(float frames, float mean, float between, float relative) {
    EMCV_PRECISE float signal = between * frames;
    EMCV_PRECISE float total = signal + relative * (mean * mean + between);
    return total > 0.0f ? signal / total : 0.0f;
}

/// The variance the budget allocates with: w pooled + (1 - w) mean (emcv_history_shrink_weight). A pixel
/// without a variance yet takes the mean (w = 0); emcv_history_no_samples() stays; without frame statistics
/// (mean <= 0 or NaN: the first frames, or a frame with no variance) the pooled value is returned as it is.
EMCV_FN float emcv_history_shrink_sigma2(float pooled, float frames, float mean, float between, float relative) {
    if (pooled == emcv_history_no_samples() || !(mean > 0.0f)) return pooled;
    if (!(pooled >= 0.0f)) return mean;
    float w = emcv_history_shrink_weight(frames, mean, between, relative);
    EMCV_PRECISE float shrunk = w * pooled + (1.0f - w) * mean;
    return shrunk;
}

/// The frame statistics, one histogram bin: adds count (1, s2, s2^2) at the bin's centre s2 = c^2
/// (c = emcv_budget_bin_sum(bin, 1, 512), the middle of the bin's sigma range) to the moments.
EMCV_FN vec3 emcv_history_moments_add(EMCV_IN(vec3) moments, uint bin, uint count) {
    float centre = emcv_budget_bin_sum(bin, 1u, 512u);
    EMCV_PRECISE float s2 = centre * centre;
    EMCV_PRECISE float c = float(count);
    return vec3(moments.x + c, moments.y + c * s2, moments.z + c * s2 * s2);
}

/// 1 / frames in the units the histogram sums it in, 2^-10 (a pixel's pooled frames are >= 1, so each adds at
/// most 1024: 2^22 pixels fit a 32-bit sum).
EMCV_FN uint emcv_history_inverse_frames_units(float frames) { return uint(1024.0f / frames + 0.5f); }

/// The next frame's prior (mean, tau^2) from the moments (pixels, sum s2, sum s2^2) of the pooled variances
/// before shrinkage and their sum of 1 / K in 2^-10 units: the observed spread S = E[s2^2] - m^2 is
/// tau^2 + E[v] with E[v] = r (m^2 + tau^2) E[1/K], so tau^2 = (S - r m^2 E[1/K]) / (1 + r E[1/K]), at least 0.
/// (0, 0) without pixels.
EMCV_FN vec2 emcv_history_frame_prior(EMCV_IN(vec3) moments, uint inverse_units, float relative) {
    if (!(moments.x > 0.0f)) return vec2(0.0f);
    EMCV_PRECISE float mean = moments.y / moments.x;
    EMCV_PRECISE float spread = moments.z / moments.x - mean * mean;
    EMCV_PRECISE float inverse = float(inverse_units) * (1.0f / 1024.0f) / moments.x;
    EMCV_PRECISE float noise = relative * inverse;
    EMCV_PRECISE float between = (spread - noise * mean * mean) / (1.0f + noise);
    return vec2(mean, max(between, 0.0f));
}

/// Budget mode's r under the tunables: a batch of EMCV_HISTORY_SPP_BUDGET samples (the mean count, at least 1)
/// of the residual's kurtosis.
EMCV_FN float emcv_history_spend_relative_variance() {
    return emcv_history_frame_relative_variance(emcv_history_residual_kurtosis(), max(EMCV_HISTORY_SPP_BUDGET, 1.0f));
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
