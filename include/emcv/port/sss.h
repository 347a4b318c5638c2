// SPDX-License-Identifier: MIT
// emcv/port/sss.h — the per-pixel screen-space SSS maths of the renderer, in the shared C++/GLSL dialect (fp32).
//
// ABOUT      Written once; the GLSL passes (shaders/render/) include it and the C++ tests call it.
//            Scaling fit s(A), search-light form (docs/frame.md, as UE uses it for sampling and
//            evaluation):            s(A) = 3.5 + 100 (A - 0.33)^4
//            Shape distance per channel (Xie & Olano 2021, section 4):           d_c = l_c / s(A_c)   (mm)
//            Radii are drawn with the widest channel d_max = max_c d_c and weighted per channel (docs/frame.md):
//                w_c = r_e R_c(r_e) / p_max(r),   r_e = sqrt(r^2 + dz_mm^2)   (depth-aware radius, docs/frame.md)
//            the output is sum_i w_c L_i / sum_i w_c per channel (constant factors cancel).
//            Sample i of N: (u_r, u_theta) = frac(R2(i) + rotation), rotation per pixel and frame from the PCG
//            hash (Cranley-Patterson rotation of the R2 sequence: each pixel gets a well stratified set, and
//            the sets of neighbouring pixels and frames decorrelate; UE5 rebases R2 the same way, docs/frame.md).
//            World to screen (docs/frame.md, exact for a perspective projection with P00 = cot(fov_x / 2)):
//                pixelsPerMm = 0.5 P00 viewportWidth / (z_view mm_per_unit)
// USAGE      vec3 d = emcv_sss_shape_distance(mfp_mm, albedo); float dmax = emcv_sss_widest(d);
//            vec2 u = emcv_sss_sample_uv(i, emcv_sss_rotation(px, py, frame, seed));
//            float r = emcv_sss_sample_radius(u.x, dmax, approximate);
//            vec3 w = emcv_sss_weight(r, emcv_sss_depth_aware_radius(r, dz_mm), d, dmax);
//            This frame's noise of the estimate, for the temporal resolve (docs/frame.md, "Temporal resolve"):
//            the pass also sums w^2, w^2 L and w^2 L^2 over its samples and stores
//            emcv_sss_noise(sum_w, sum_w2, sum_w2l, sum_w2l2, estimate, n).
#ifndef EMCV_PORT_SSS_H
#define EMCV_PORT_SSS_H

#include "burley.h"
#include "hash.h"

EMCV_PORT_BEGIN

/// s(A) = 3.5 + 100 (A - 0.33)^4: Christensen-Burley search-light fit (docs/frame.md).
EMCV_FN float emcv_sss_scaling(float albedo) {
    float a = albedo - 0.33f;
    float a2 = a * a;
    return 3.5f + 100.0f * a2 * a2;
}

/// d_c = l_c / s(A_c) per channel, in the unit of the mean free path (mm). Xie & Olano 2021, section 4.
EMCV_FN vec3 emcv_sss_shape_distance(vec3 mean_free_path_mm, vec3 albedo) {
    return vec3(mean_free_path_mm.x / emcv_sss_scaling(albedo.x),
                mean_free_path_mm.y / emcv_sss_scaling(albedo.y),
                mean_free_path_mm.z / emcv_sss_scaling(albedo.z));
}

/// The widest channel's shape distance: radii are drawn from its profile (docs/frame.md, HDRP's shapeParam.w).
EMCV_FN float emcv_sss_widest(vec3 d) {
    return max(d.x, max(d.y, d.z));
}

/// Screen pixels per millimetre at view depth z_view (world units, > 0): 0.5 P00 W / (z mm_per_unit) (docs/frame.md).
EMCV_FN float emcv_sss_pixels_per_mm(float p00, float viewport_width, float z_view, float mm_per_unit) {
    return 0.5f * p00 * viewport_width / (z_view * mm_per_unit);
}

/// The per-pixel, per-frame rotation of the sample set, uniform in [0, 1)^2 (PCG hash, port/hash.h).
EMCV_FN vec2 emcv_sss_rotation(uint pixel_x, uint pixel_y, uint frame, uint seed) {
    uint h = emcv_pcg(pixel_x ^ emcv_pcg(pixel_y ^ emcv_pcg(frame ^ emcv_pcg(seed))));
    return vec2(emcv_uint_to_unit_float(h), emcv_uint_to_unit_float(emcv_pcg(h)));
}

/// Sample i's (u_r, u_theta) in [0, 1)^2: the R2 point i rotated by `rotation` (Cranley-Patterson).
EMCV_FN vec2 emcv_sss_sample_uv(uint i, vec2 rotation) {
    vec2 p = emcv_r2(i) + rotation;
    return p - floor(p);
}

/// Sample i's (u_r, u_theta) in [0, 1)^2 for `burley-sobol-N`: Sobol's (0, 2)-sequence (emcv_sobol2_bits) with its
/// bits XOR-scrambled by the pixel's `rotation` (its 24 bits, emcv_sss_rotation): a random digit scrambling, which
/// keeps every elementary interval's one point (the stratification) where R2's rotation keeps only its low
/// discrepancy.
EMCV_FN vec2 emcv_sss_sample_uv_sobol(uint i, vec2 rotation) {
    uvec2 scramble = uvec2(uint(rotation.x * 16777216.0f) << 8u, uint(rotation.y * 16777216.0f) << 8u);
    uvec2 bits = emcv_sobol2_bits(i) ^ scramble;
    return vec2(emcv_uint_to_unit_float(bits.x), emcv_uint_to_unit_float(bits.y));
}

/// A radius (mm) with pdf p(r; d): the exact inverse CDF, or SPVG's approximation when `approximate`
/// (whose true density differs slightly: the weight still divides by the exact pdf, docs/frame.md).
EMCV_FN float emcv_sss_sample_radius(float u, float d, bool approximate) {
    if (approximate) return emcv_burley_sample_spvg(u, d);
    return emcv_burley_sample_exact(u, d);
}

/// Offset in pixels of a sample at radius r_mm and angle 2 pi u_theta (pixels are square: no aspect term).
EMCV_FN vec2 emcv_sss_offset_pixels(float r_mm, float u_theta, float pixels_per_mm) {
    float theta = 2.0f * emcv_burley_pi() * u_theta;
    float r_px = r_mm * pixels_per_mm;
    return vec2(r_px * cos(theta), r_px * sin(theta));
}

/// r_e = sqrt(r^2 + dz^2): the distance through the surface's depth step (docs/frame.md, in mm here).
EMCV_FN float emcv_sss_depth_aware_radius(float r_mm, float dz_mm) {
    return sqrt(r_mm * r_mm + dz_mm * dz_mm);
}

/// Per-channel weight r_e R_c(r_e) / p_max(r) of one sample drawn at radius r with the widest channel
/// d_sample (docs/frame.md; the profile at r_e, the pdf at r, as UE with RESAMPLE_PDF 0).
EMCV_FN vec3 emcv_sss_weight(float r_mm, float r_e_mm, vec3 d, float d_sample) {
    float rcp_pdf = 1.0f / emcv_burley_pdf(r_mm, d_sample);
    return vec3(emcv_burley_profile_r(r_e_mm, d.x), emcv_burley_profile_r(r_e_mm, d.y),
                emcv_burley_profile_r(r_e_mm, d.z)) * rcp_pdf;
}

/// emcv_sss_noise's code for an estimate without noise: no sample taken (a kernel narrower than a pixel keeps
/// the pixel's own irradiance, exactly).
EMCV_FN float emcv_sss_noise_exact() { return -2.0f; }

/// emcv_sss_noise's code for an estimate whose noise one frame cannot tell: fewer than two effective samples in
/// a channel (below).
EMCV_FN float emcv_sss_noise_unknown() { return -1.0f; }

/// Per channel, the per-sample variance of the ratio estimate R = sum(w L) / sum(w) over n samples, from the
/// sums the sampling loop keeps: the delta method's variance of a ratio estimator (Cochran 1977, 6.3),
///     Var(R) ~ sum w_i^2 (L_i - R)^2 / (sum w)^2,
/// times n / (n - 1) for the degree of freedom R takes from its own residuals, and times n per sample. The
/// square is expanded, sum w^2 L^2 - 2 R sum w^2 L + R^2 sum w^2, floored at 0 (rounding). The samples are
/// treated as independent: the renderer's stratified (rotated R2) samples vary less than that, so this
/// overestimates their noise (docs/frame.md). Needs n >= 2 and sum_w > 0 in every channel.
EMCV_FN vec3 emcv_sss_sample_variance(vec3 sum_w, vec3 sum_w2, vec3 sum_w2l, vec3 sum_w2l2, vec3 estimate, uint n) {
    vec3 squares = max(sum_w2l2 - 2.0f * estimate * sum_w2l + estimate * estimate * sum_w2, vec3(0.0f));
    float nf = float(n);
    return (nf * nf / (nf - 1.0f)) * squares / (sum_w * sum_w);
}

/// The noise code a pass stores beside its estimate (one float): the largest channel's per-sample variance
/// (emcv_sss_sample_variance), emcv_sss_noise_exact() for n = 0, emcv_sss_noise_unknown() when one frame
/// cannot tell. The largest channel: the resolve applies one deviation to every channel, and a box too wide
/// keeps noise where one too narrow would drop a good history. One frame cannot tell where a channel has fewer
/// than two effective samples, (sum w)^2 / sum w^2 < 2 (Kish's effective sample size; a channel that accepted
/// none has 0): where one sample's weight dominates, R is that sample's value and every residual the delta
/// method sees is small, whatever the sample hit. On the renderer's shadowed rims such estimates were a tenth of
/// the deviation the bright sample put into the pixel (docs/frame.md, "The noise box").
EMCV_FN float emcv_sss_noise(vec3 sum_w, vec3 sum_w2, vec3 sum_w2l, vec3 sum_w2l2, vec3 estimate, uint n) {
    if (n == 0u) return emcv_sss_noise_exact();
    if (n < 2u || !(sum_w.x > 0.0f && sum_w.y > 0.0f && sum_w.z > 0.0f)) return emcv_sss_noise_unknown();
    vec3 effective = sum_w * sum_w / sum_w2;  // Kish's effective sample size per channel
    if (min(effective.x, min(effective.y, effective.z)) < 2.0f) return emcv_sss_noise_unknown();
    vec3 v = emcv_sss_sample_variance(sum_w, sum_w2, sum_w2l, sum_w2l2, estimate, n);
    return max(v.x, max(v.y, v.z));
}

EMCV_PORT_END

#endif  // #ifndef EMCV_PORT_SSS_H
