// SPDX-License-Identifier: MIT
// emcv/port/history.h — the adaptive SSS methods' per-pixel history (spvg, cv, cv-notex) in the shared
// C++/GLSL dialect (fp32): what a history texel holds, when it may be reused, and the sample count it asks for.
//
// ABOUT      docs/renderer.md documents each layout and the choices (the per-pixel study, emcv-cvstudy):
//              spvg, cv-notex  one RGBA16F texel: (mean, variance / target, count, 0) of the tracked scalar
//                              (spvg: gamma-space luminance f; cv-notex: the residual f - G, alpha = 1).
//                              The variance is stored divided by the target so that what decides N stays far
//                              above binary16's smallest normal (6.1e-5; a variance under it read as 0 would
//                              give N = 0 under n_min = 0).
//              cv              RGBA32F (C_ff, C_fG, C_GG, count) + RG32F (mean_f, mean_G): the covariances stay
//                              fp32 because C_ff - C_fG^2 / C_GG cancels (binary16 covariances gave N = 0 on
//                              0.2% of flicker frames in the study); the means too, because G is an in-frame
//                              constant: a mean of G rounded to half makes a static G push G - half(G) every
//                              frame, a phantom C_GG and alpha (measured on `static`).
//            The count saturates at EMCV_HISTORY_MAX_COUNT (exact in binary16). A texel that is not finite, has
//            a negative variance or count, is refused: the pixel restarts (never spreads NaN/Inf).
//            A history younger than two frames has no variance yet and asks for n_max (as on a reset), not
//            for the 0 that n_min = 0 would give.
// USAGE      EmcvMovingStats s; bool ok = emcv_history_decode_stats(texel, s);  int n = emcv_history_count_spvg(s);
// REFERENCES Xie & Olano 2021 (Xie & Olano 2021, section 4-5); SPVG 2020 (eta 0.2, N = clamp(var / 1e-4, 8, 64)).
#ifndef EMCV_PORT_HISTORY_H
#define EMCV_PORT_HISTORY_H

#include "port.h"
#include "cv.h"
#include "ema.h"
#include "samples.h"

EMCV_PORT_BEGIN

// Tunables: each may be set before this header is included (`#define NAME value`, or the renderer's
// `--define NAME=VALUE`, which demo/render/tunables.cpp validates against the ranges given here).

/// SPVG's target variance of the gamma-space luminance. Range: (0, 1].
#ifndef EMCV_HISTORY_TARGET
#define EMCV_HISTORY_TARGET 1.0e-4f
#endif
/// The most samples a pixel takes in a frame. Range: [1, 1024] integer, >= every N_MIN.
#ifndef EMCV_HISTORY_N_MAX
#define EMCV_HISTORY_N_MAX 64
#endif
/// spvg's fewest samples per SSS pixel. Range: [0, N_MAX] integer.
#ifndef EMCV_HISTORY_SPVG_N_MIN
#define EMCV_HISTORY_SPVG_N_MIN 8
#endif
/// The control-variate methods' fewest samples where the kernel is wider than a pixel (cv, cv-notex).
/// Range: [0, N_MAX] integer.
#ifndef EMCV_HISTORY_RESIDUAL_N_MIN
#define EMCV_HISTORY_RESIDUAL_N_MIN EMCV_HISTORY_SPVG_N_MIN
#endif
/// SPVG's moving mean/variance weight (spvg, cv-notex). Range: (0, 1].
#ifndef EMCV_HISTORY_ETA_MOVING
#define EMCV_HISTORY_ETA_MOVING 0.2f
#endif
/// The EMCM weight of cv (the paper's; chosen by the study, docs/renderer.md). Range: (0, 1].
#ifndef EMCV_HISTORY_ETA_EMCM
#define EMCV_HISTORY_ETA_EMCM 0.05f
#endif
/// Saturating frame count of a history texel, an integer exact in binary16. Range: [2, 2048] unsigned.
#ifndef EMCV_HISTORY_MAX_COUNT
#define EMCV_HISTORY_MAX_COUNT 1024u
#endif

/// Gamma-space luminance (Rec. 709 weights, gamma 1/2.2) of a linear colour: the scalar SPVG tracks.
/// `precise` and written out (not dot()): every shader that tracks this value must get the same bits, and a
/// compiler free to contract the sum into FMAs does it differently per shader (measured: 2 binary16 ulps of
/// the stored variance apart between the update pass and a probe shader).
EMCV_FN float emcv_gamma_luminance(EMCV_IN(vec3) linear_rgb) {
    EMCV_PRECISE float y = 0.2126f * linear_rgb.x + 0.7152f * linear_rgb.y + 0.0722f * linear_rgb.z;
    return pow(max(y, 0.0f), 1.0f / 2.2f);
}

/// (mean, variance / target, count, 0) -> moving stats. False (and s reset) when the texel is poisoned:
/// not finite, a negative variance, a negative or fractional count.
EMCV_FN bool emcv_history_decode_stats(EMCV_IN(vec4) texel, EMCV_OUT(EmcvMovingStats) s) {
    s = emcv_moving_stats_init();
    bool finite = emcv_is_finite(texel.x) && emcv_is_finite(texel.y) && emcv_is_finite(texel.z);
    if (!finite || texel.y < 0.0f || texel.z < 0.0f || texel.z != floor(texel.z)) return false;
    s.mean = texel.x;
    s.variance = texel.y * EMCV_HISTORY_TARGET;
    s.count = uint(texel.z);
    return true;
}

/// SPVG / cv-notex history texel: (mean, variance / EMCV_HISTORY_TARGET, count capped at
/// EMCV_HISTORY_MAX_COUNT, 0), the inverse of emcv_history_decode_stats.
EMCV_FN vec4 emcv_history_encode_stats(EMCV_IN(EmcvMovingStats) s) {
    return vec4(s.mean, s.variance / EMCV_HISTORY_TARGET, float(min(s.count, EMCV_HISTORY_MAX_COUNT)), 0.0f);
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

/// Reprojection test (SPVG's reset on failed reprojection): the previous frame's pixel under the reprojected
/// position must show the same material, a linear depth within 5% of where this surface point was then, and a
/// normal within ~25 degrees. Off-screen positions are the caller's test.
EMCV_FN bool emcv_history_reusable(uint material, uint prev_material, float expected_prev_depth, float prev_depth,
                                   EMCV_IN(vec3) normal, EMCV_IN(vec3) prev_normal) {
    if (material == 0u || material != prev_material) return false;
    if (!(abs(prev_depth - expected_prev_depth) <= 0.05f * expected_prev_depth)) return false;
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

/// spvg: N = clamp(var / 1e-4, 8, 64); n_max until the history has two frames.
EMCV_FN int emcv_history_count_spvg(EMCV_IN(EmcvMovingStats) s) {
    if (s.count < 2u) return EMCV_HISTORY_N_MAX;
    return emcv_sample_count(s.variance, EMCV_HISTORY_TARGET, EMCV_HISTORY_SPVG_N_MIN, EMCV_HISTORY_N_MAX);
}

/// The control-variate methods' count from a residual variance: clamp(var / target, RESIDUAL_N_MIN, N_MAX),
/// NaN -> N_MAX. The floor keeps a static scene sampled as SPVG samples it, so the gain comes from the residual
/// variance staying low when the light changes; a variance of exactly 0 never means "no samples" (a history
/// stored in half precision can repeat bit for bit), only a sub-pixel kernel does (emcv_history_sub_pixel).
/// docs/renderer.md has the measurements behind both choices.
EMCV_FN int emcv_history_count_residual(float residual_variance) {
    return emcv_sample_count(residual_variance, EMCV_HISTORY_TARGET, EMCV_HISTORY_RESIDUAL_N_MIN, EMCV_HISTORY_N_MAX);
}

/// cv-notex: the moving variance of r = f - G (alpha = 1).
EMCV_FN int emcv_history_count_notex(EMCV_IN(EmcvMovingStats) s) {
    if (s.count < 2u) return EMCV_HISTORY_N_MAX;
    return emcv_history_count_residual(s.variance);
}

/// cv's floor while its history is settling after a light change (docs/renderer.md, "Settling after a change").
/// Range: [0, N_MAX] integer; 0 (or anything up to RESIDUAL_N_MIN) turns the settling floor off.
#ifndef EMCV_HISTORY_CV_SETTLE_N
#define EMCV_HISTORY_CV_SETTLE_N 11
#endif

/// cv: Var(f - alpha G) = C_ff - C_fG^2 / C_GG from the EMCM (the joint optimum of N and alpha), with the
/// settling floor while the light change still explains more of f's variance than the residual does
/// (C_fG^2 / C_GG > the residual variance). A static light has C_GG = 0 and never settles.
EMCV_FN int emcv_history_count_cv(EMCV_IN(EmcvEmcm2) s) {
    if (s.count < 2u) return EMCV_HISTORY_N_MAX;
    float residual = emcv_cv_optimal_residual_variance_emcm2(s);
    int n = emcv_history_count_residual(residual);
    EMCV_PRECISE float explained = s.cov.x - residual;
    if (explained > residual) n = max(n, EMCV_HISTORY_CV_SETTLE_N);
    return n;
}

EMCV_PORT_END

#endif  // #ifndef EMCV_PORT_HISTORY_H
