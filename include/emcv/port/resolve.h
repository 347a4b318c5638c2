// SPDX-License-Identifier: MIT
/// \file
/// emcv/port/resolve.h — the per-pixel maths of a temporal resolve (TAA without jitter) after the SSS, as
/// engines resolve a stochastic SSS before display: the history, reprojected with the motion vectors, is clipped
/// to the current frame's 3x3 neighbourhood in YCoCg (variance clipping) and blended exponentially with the
/// current pixel (at a higher weight where the history, or its neighbourhood's mean, lay beyond this frame's
/// noise, or where the guide that moved the history changed by much of its spread). The demo's `resolve`
/// pass (shaders/render/resolve.comp.glsl) runs it; docs/frame.md,
/// "Temporal resolve", states the choices and their sources.
//
// TUNABLES   EMCV_RESOLVE_BLEND ........ weight of the current frame in the blend, (0, 1]; default 0.1
//            EMCV_RESOLVE_CLIP_SIGMA ... half-width of the clip box in neighbourhood standard deviations,
//                                        (0, 4]; default 1
//            EMCV_RESOLVE_GUIDE ........ 1: the history follows the change of a noise-free guide
//                                        (emcv_resolve_guided_history), 0: off; default 1
//            EMCV_RESOLVE_GUIDE_TAPS ... taps of the guide's fixed Burley estimate of the scattered light,
//                                        [0, 64] (0: the unscattered light); default 16
#ifndef EMCV_PORT_RESOLVE_H
#define EMCV_PORT_RESOLVE_H

#include "history.h"
#include "port.h"
#include "tonemap.h"

/// Weight of the current frame in the exponential blend. At 0.1 a converged history averages about
/// (2 - 0.1) / 0.1 = 19 frames of independent noise (its variance is 0.1 / (2 - 0.1) of one frame's, -12.8 dB),
/// and a change the clip lets through is 90% taken up after 22 frames; engines ship 0.04-0.1 (Karis 2014).
/// Range (0, 1]; 1 shows the raw frame.
#ifndef EMCV_RESOLVE_BLEND
#define EMCV_RESOLVE_BLEND 0.1f
#endif

/// Half-width of the clip box around the neighbourhood mean, in the neighbourhood's standard deviations
/// (Salvi 2016's variance clipping, gamma = 1). Range (0, 4].
#ifndef EMCV_RESOLVE_CLIP_SIGMA
#define EMCV_RESOLVE_CLIP_SIGMA 1.0f
#endif

/// 1: the reprojected history is moved by the change that a noise-free guide image shows at the pixel since the
/// history was made, in proportion to how much of the guide's detail the pixel's neighbourhood follows
/// (emcv_resolve_guide_slope, emcv_resolve_guided_history); 0: the history as reprojected. A switch for
/// comparisons (docs/frame.md, "The guide"), not a value to tune. Range {0, 1}.
#ifndef EMCV_RESOLVE_GUIDE
#define EMCV_RESOLVE_GUIDE 1
#endif

/// The guide at a scattering pixel: the scattered light as a Burley estimate of this many taps at one fixed
/// rotation (the same taps every frame, so the estimate carries no noise from frame to frame, only a fixed
/// quadrature error that follows the image), times the albedo; 0: the unscattered light times the albedo. What
/// the guide is for is to show how resampling the history and a changing view or light move the scattered light
/// (emcv_resolve_guided_history): the unscattered light shows sharp shadow edges and relief that the scattered
/// light has blurred, and not how the screen-space kernel's view of the surface changes as the camera turns.
/// 16 was chosen on `moving` alone as the smallest count within 0.5 dB of 32 taps for `burley-8`'s resolved image
/// (4, 8, 16, 32 taps: +5.0, +6.4, +7.6, +8.0 dB over its raw frames; 0 taps +5.2), and is reported on the other
/// scenes (docs/frame.md, "The guide"). Range [0, 64].
#ifndef EMCV_RESOLVE_GUIDE_TAPS
#define EMCV_RESOLVE_GUIDE_TAPS 16
#endif

EMCV_PORT_BEGIN

/// Half-width of the noise box (emcv_resolve_narrow_to_noise) in standard deviations of this frame's own noise.
/// A history that this frame's expectation agrees with is clipped only where this frame's deviation exceeds
/// that many standard deviations: under a normal noise on 0.3% of frames per channel, and by Chebyshev's bound
/// on at most 1 / 3^2 = 11% whatever the noise's distribution (Burley samples are heavy-tailed). The standard
/// deviation is the renderer's estimate from one frame's samples, which overestimates the stratified
/// sampling's (docs/frame.md). Range (0, 16].
#ifndef EMCV_RESOLVE_NOISE_SIGMA
#define EMCV_RESOLVE_NOISE_SIGMA 3.0f
#endif

/// RGB to YCoCg (luma, orange and green chroma): an exact, invertible basis in which a box around the
/// neighbourhood follows its luma and its hue separately.
EMCV_FN vec3 emcv_rgb_to_ycocg(EMCV_IN(vec3) c) {
    return vec3(0.25f * c.x + 0.5f * c.y + 0.25f * c.z, 0.5f * c.x - 0.5f * c.z, -0.25f * c.x + 0.5f * c.y - 0.25f * c.z);
}

/// The inverse of emcv_rgb_to_ycocg.
EMCV_FN vec3 emcv_ycocg_to_rgb(EMCV_IN(vec3) c) {
    return vec3(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z);
}

/// The population variance per channel of n values from the sums of their values and squares, floored at 0
/// (the sums' rounding can make it slightly negative).
EMCV_FN vec3 emcv_resolve_variance(EMCV_IN(vec3) sum, EMCV_IN(vec3) sum_squares, float n) {
    vec3 mean = sum / n;
    return max(sum_squares / n - mean * mean, vec3(0.0f));
}

/// The clip box of a neighbourhood of n values from the sums of its values and squares, per channel: mean -+
/// EMCV_RESOLVE_CLIP_SIGMA standard deviations (population variance, floored at 0), grown to hold the pixel's
/// own current value. Without that a pixel that stands out of its neighbourhood (a highlight's peak, an edge)
/// would clip even a history equal to itself, and a still image would not resolve to itself. Growing the box to
/// the neighbourhood's whole range instead would keep more of a noisy history, but also the old image after a
/// light change (a one-off trial on light-off, docs/frame.md).
EMCV_FN void emcv_resolve_clip_box(EMCV_IN(vec3) sum, EMCV_IN(vec3) sum_squares, float n, EMCV_IN(vec3) current,
                                   EMCV_OUT(vec3) lo, EMCV_OUT(vec3) hi) {
    vec3 mean = sum / n;
    vec3 deviation = sqrt(emcv_resolve_variance(sum, sum_squares, n));
    lo = min(mean - float(EMCV_RESOLVE_CLIP_SIGMA) * deviation, current);
    hi = max(mean + float(EMCV_RESOLVE_CLIP_SIGMA) * deviation, current);
}

/// The YCoCg half-widths of a box that holds a display-space RGB deviation `rgb_deviation` whatever the signs its
/// channels take (|M| |d| for the YCoCg matrix M): the channels of one estimate move together, in one direction
/// or apart, and a box for either holds both.
EMCV_FN vec3 emcv_resolve_ycocg_extent(EMCV_IN(vec3) rgb_deviation) {
    vec3 d = abs(rgb_deviation);
    float luma_like = 0.25f * d.x + 0.5f * d.y + 0.25f * d.z;  // Y's and Cg's weights are the same in magnitude
    return vec3(luma_like, 0.5f * (d.x + d.z), luma_like);
}

/// The noise box's YCoCg half-widths at a pixel whose exposed linear value is `exposed` (display value `shown`:
/// emcv_display_encode of it) for an exposed linear deviation `deviation` per channel: the deviation carried
/// through the display encoding upwards and downwards from the pixel's value, the larger of the two per channel,
/// then bounded in YCoCg for every sign pattern (emcv_resolve_ycocg_extent). The encoding is not linear: sRGB is
/// concave, so a deviation downwards is the larger in display values there, and ACES's toe is convex, where the
/// upward one is; a box sized one way alone is too narrow the other, and takes for wrong a history that this
/// frame's noise explains (docs/frame.md, "The noise box").
EMCV_FN vec3 emcv_resolve_noise_extent(EMCV_IN(vec3) exposed, EMCV_IN(vec3) shown, EMCV_IN(vec3) deviation, int tonemap) {
    vec3 up = emcv_display_encode(exposed + deviation, tonemap) - shown;
    vec3 down = shown - emcv_display_encode(exposed - deviation, tonemap);
    return emcv_resolve_ycocg_extent(max(abs(up), abs(down)));
}

/// The variance of this frame's SSS estimate at a pixel that took n samples: the larger of its own per-sample
/// variance `own` (emcv_sss_noise) and the mean of its 3x3 neighbourhood's (`sum` of the `known` ones >= 0, the
/// pixel's own among them), over n. Neighbouring kernels cover nearly the same surface, so the mean is steadier
/// than one pixel's few samples, which may all miss a bright region the kernel reaches; the pixel's own is kept
/// where it is larger, since its samples saw what its value holds (one sample that hit a bright spot the
/// neighbours' missed). Negative (no noise box) where the pixel's own is unknown (fewer than two samples): its
/// neighbours, which did not see what its one sample saw, cannot vouch for it (pooled alone, a single bright
/// sample's value was taken as this frame's truth and held the history to it: docs/frame.md). 0 for n = 0.
EMCV_FN float emcv_resolve_pooled_noise(float own, float sum, float known, uint n) {
    if (n == 0u) return 0.0f;
    if (own < 0.0f || !(known > 0.0f)) return -1.0f;
    return max(own, sum / known) / float(n);
}

/// The clip box [lo, hi] narrowed to this frame's own noise: to current -+ extent (emcv_resolve_ycocg_extent of
/// EMCV_RESOLVE_NOISE_SIGMA of its standard deviations). The neighbourhood's box holds detail besides noise, so
/// at an edge or relief under a moving camera it is wide and keeps a resampled history whose error is no noise
/// of this frame; the noise box keeps a history only as far from this frame's value as this frame's noise could
/// take it. Where the frame has no noise (a pixel that does not scatter, a method without sampling) the box
/// closes on the current value (emcv_resolve_clip keeps half an 8-bit step) and the resolve shows the frame as
/// it is. Both boxes hold the current value, so the narrowed one does too.
EMCV_FN void emcv_resolve_narrow_to_noise(EMCV_IN(vec3) current, EMCV_IN(vec3) extent, EMCV_INOUT(vec3) lo,
                                          EMCV_INOUT(vec3) hi) {
    lo = max(lo, current - extent);
    hi = min(hi, current + extent);
}

/// The history moved along the line towards `target`, a colour inside the box [lo, hi], until it lies in the box
/// (a clip, not a per-channel clamp): the clipped colour is a mix of the history and the target, never a hue
/// that neither holds. The resolve's target is emcv_resolve_target (the current value filtered over its 3x3
/// neighbourhood with the raw value's detail put back), itself clipped towards the current value into the box:
/// an estimate of what this frame shows at the pixel with less noise than the pixel alone. Clipping towards the
/// box's centre, the neighbourhood's plain mean, pulls edges and relief towards their neighbours' average, a blur
/// the next frames keep; towards the raw current value, it keeps more of that value's noise; towards the filtered
/// value alone, less blur than the centre, but still a blur (all measured, docs/frame.md "Temporal resolve").
/// Inside the box the history is kept unchanged. The box is at least half an 8-bit display step wide on every
/// side: a flat channel (zero spread) would otherwise clip the history's rounding error and pull a still pixel
/// off its value, by differences the display cannot show.
EMCV_FN vec3 emcv_resolve_clip(EMCV_IN(vec3) history, EMCV_IN(vec3) target, EMCV_IN(vec3) lo, EMCV_IN(vec3) hi) {
    vec3 centre = 0.5f * (lo + hi);
    vec3 extent = max(0.5f * (hi - lo), vec3(0.5f / 255.0f));
    vec3 low = centre - extent;
    vec3 high = centre + extent;
    vec3 offset = history - target;
    // The largest t in [0, 1] with target + t offset inside [low, high], channel by channel.
    float t = 1.0f;
    for (int c = 0; c < 3; ++c) {
        if (offset[c] > 0.0f) t = min(t, (high[c] - target[c]) / offset[c]);
        if (offset[c] < 0.0f) t = min(t, (low[c] - target[c]) / offset[c]);
    }
    return target + max(t, 0.0f) * offset;
}

/// The clip's target: the pixel's filtered current value plus the part of its raw value's deviation from it that
/// is detail, not noise (a local Wiener filter, Lee 1980). The current 3x3 neighbourhood's variance S holds the
/// image's detail and this frame's noise; the reprojected history's own 3x3 neighbourhood, averaged over about
/// 19 frames, holds the detail alone (its noise is 0.1 / (2 - 0.1) of a frame's at the default blend), variance
/// D. The fraction of the raw deviation that is signal is then D / S, at most 1 (summed over the channels: one
/// fraction for the colour, so that the target lies on the line from the filtered to the raw value, a colour
/// between two that this frame shows; a fraction per channel mixes the raw luma with the filtered chroma, and
/// the clip then drags a history that equals the raw value to that other hue). Where the history shows as much
/// spread as this frame (detail, or a light that went down) the target is the raw value, which keeps relief and
/// edges; where it shows none (flat skin under noise) it is the filtered value, which keeps the noise out; a
/// history without neighbours on its surface (D = 0) gives the filtered value. Nothing here is a constant to
/// choose. Measured against the filtered value alone and the raw value alone: docs/frame.md, "Where the clip
/// points".
EMCV_FN vec3 emcv_resolve_target(EMCV_IN(vec3) current, EMCV_IN(vec3) filtered, EMCV_IN(vec3) neighbourhood_variance,
                                 EMCV_IN(vec3) history_variance) {
    float spread = neighbourhood_variance.x + neighbourhood_variance.y + neighbourhood_variance.z;
    float detail = history_variance.x + history_variance.y + history_variance.z;
    float signal = spread > detail ? detail / spread : 1.0f;
    return filtered + signal * (current - filtered);
}

/// The weight of the neighbour at (dx, dy), each in {-1, 0, 1}, in the 3x3 filter of the clip's target: the
/// binomial (1 2 1) x (1 2 1) / 16, the smallest separable low-pass that keeps the pixel itself the heaviest tap
/// (a Gaussian of about 0.7 px, as engines filter the current frame for their clip).
EMCV_FN float emcv_resolve_filter_weight(int dx, int dy) {
    return float((2 - abs(dx)) * (2 - abs(dy))) * 0.0625f;
}

/// The Catmull-Rom weights of the four texels around a sample at fraction t in [0, 1) past the second texel
/// (texels at -1, 0, 1, 2): the cubic that interpolates them with continuous slope, sharp enough that resampling
/// a moving history every frame does not blur it as bilinear weights do. They sum to 1; t = 0 gives (0, 1, 0, 0).
EMCV_FN vec4 emcv_resolve_catmull_rom(float t) {
    return vec4(t * (-0.5f + t * (1.0f - 0.5f * t)), 1.0f + t * t * (-2.5f + 1.5f * t), t * (0.5f + t * (2.0f - 1.5f * t)),
                t * t * (-0.5f + 0.5f * t));
}

/// The current value's weight that minimises the error of mixing it (unbiased, variance sigma^2) with a history
/// off by b: at weight w the expected squared error is (1 - w)^2 b^2 + w^2 sigma^2, least at b^2 / (b^2 + sigma^2).
/// `bias_squared` is b^2 in units of sigma^2. emcv_resolve_current_weight, emcv_resolve_shift_weight and
/// emcv_resolve_guide_weight estimate b three ways.
EMCV_FN float emcv_resolve_least_error_weight(float bias_squared) {
    return bias_squared / (bias_squared + 1.0f);
}

/// The current value's weight in the blend: EMCV_RESOLVE_BLEND, or k^2 / (k^2 + 1) (k = EMCV_RESOLVE_NOISE_SIGMA,
/// 0.9 at k = 3) where the history lay beyond the noise box `noise_extent` around the current value
/// (emcv_resolve_narrow_to_noise) in any channel, whichever is larger. Such a history differs from this frame by
/// more than k standard deviations of its noise: it is wrong (a change of the lighting, a resampled edge under a
/// moving camera, aliased detail), not noisy. What the clip keeps of it lies on the box's edge, up to k standard
/// deviations sigma from the current value, an error the blend would hand on to the next frames at its full
/// weight: b = k sigma in emcv_resolve_least_error_weight, w = k^2 / (k^2 + 1). A history
/// inside the box keeps the blend's weight: there the difference is what this frame's noise explains. No
/// constant besides the box's own k. Only where a noise box applies (the caller's test).
EMCV_FN float emcv_resolve_current_weight(EMCV_IN(vec3) history, EMCV_IN(vec3) current, EMCV_IN(vec3) noise_extent) {
    bool beyond = false;
    for (int c = 0; c < 3; ++c) beyond = beyond || abs(history[c] - current[c]) > noise_extent[c];
    float k2 = float(EMCV_RESOLVE_NOISE_SIGMA) * float(EMCV_RESOLVE_NOISE_SIGMA);
    return beyond ? max(float(EMCV_RESOLVE_BLEND), emcv_resolve_least_error_weight(k2)) : float(EMCV_RESOLVE_BLEND);
}

/// The current value's weight where the history's neighbourhood as a whole has moved off this frame's: 0, or
/// (z^2 - 1) / (z^2 - 1 + n) where z > k (k = EMCV_RESOLVE_NOISE_SIGMA). `mean_difference` is the mean of the
/// current 3x3 neighbourhood less the mean of the history's 3x3 texels around the reprojected position (n = 9
/// values each, all on this surface), `noise_extent` the pixel's noise box (k standard deviations sigma per
/// channel, emcv_resolve_noise_extent). A change of the lighting that each frame keeps inside the noise (a slow
/// fade: the history lags it by a little more every frame), or a history that resampling has moved off this
/// frame's values, shifts the neighbourhood together, while this frame's noise, independent from pixel to pixel,
/// averages down to sigma / sqrt(n) in the mean. z is the largest channel's difference in those units. The test
/// is the noise box's own, at the mean's noise: a shift of more than k of its standard deviations is not this
/// frame's noise (a normal noise exceeds it on 0.3% of frames per channel; Chebyshev: at most 1 / k^2). Then
/// z^2 - 1 is the method-of-moments estimate of the squared shift b^2 in units of sigma^2 / n (E[z^2] = 1 + n b^2 /
/// sigma^2), and the weight returned is emcv_resolve_least_error_weight's for it, (z^2 - 1) / (z^2 - 1 + n). No
/// constant but n and k.
EMCV_FN float emcv_resolve_shift_weight(EMCV_IN(vec3) mean_difference, EMCV_IN(vec3) noise_extent, float n) {
    float z2 = 0.0f;
    for (int c = 0; c < 3; ++c) {
        if (noise_extent[c] > 0.0f) {
            float z = mean_difference[c] * float(EMCV_RESOLVE_NOISE_SIGMA) * sqrt(n) / noise_extent[c];
            z2 = max(z2, z * z);
        }
    }
    float k2 = float(EMCV_RESOLVE_NOISE_SIGMA) * float(EMCV_RESOLVE_NOISE_SIGMA);
    return z2 > k2 ? emcv_resolve_least_error_weight((z2 - 1.0f) / n) : 0.0f;
}

/// Whether a guide channel shows detail to regress on over n values whose centred sum of squares is
/// `guide_variance_sum`: its standard deviation is at least half an 8-bit display step (the clip box's floor,
/// emcv_resolve_clip). Below that the slope (emcv_resolve_guide_slope) and its uncertainty
/// (emcv_resolve_guide_weight) are 0: the guide's spread there is its own rounding.
EMCV_FN bool emcv_resolve_guide_shows_detail(float guide_variance_sum, float n) {
    return guide_variance_sum > n * (0.5f / 255.0f) * (0.5f / 255.0f);
}

/// The guide slope per channel: how much of the guide's detail the resolved values follow around a pixel, the
/// least-squares slope b of the local linear model value = a + b guide over its 3x3 neighbourhood (the guided
/// filter's model, He et al. 2010), from the neighbourhood's centred sums: `guide_variance_sum` = sum of
/// (g - mean g)^2, `covariance_sum` = sum of (g - mean g) (v - mean v). This frame's noise is in the values, not
/// in the guide, so it does not bias b (it is independent of g); it spreads it, and b is clamped to [0, 1]: the
/// scattered light holds at most the unscattered light's detail (a blur never sharpens) and does not invert
/// it. Where the guide's 3x3 standard deviation is under half an 8-bit display step (the clip box's floor,
/// emcv_resolve_clip), the guide shows no detail to regress on and the slope is 0.
EMCV_FN vec3 emcv_resolve_guide_slope(EMCV_IN(vec3) guide_variance_sum, EMCV_IN(vec3) covariance_sum, float n) {
    vec3 slope = vec3(0.0f);
    for (int c = 0; c < 3; ++c)
        if (emcv_resolve_guide_shows_detail(guide_variance_sum[c], n))
            slope[c] = clamp(covariance_sum[c] / guide_variance_sum[c], 0.0f, 1.0f);
    return slope;
}

/// The current value's weight where the guide's correction of the history is uncertain: the largest over the
/// channels whose guide shows detail (emcv_resolve_guide_shows_detail) of emcv_resolve_least_error_weight(d^2 /
/// S), where d is the guide's change at the pixel (`guide_change`: guide - guide_history, what
/// emcv_resolve_guided_history moves the history by, times the slope) and S the guide's centred sum of squares
/// over the n values the slope was fitted on (`guide_variance_sum`); 0 elsewhere. The least-squares slope of
/// values with noise of variance sigma^2 about the local linear model has variance sigma^2 / S (fixed
/// regressors: the guide has no noise), so the moved history is off by (b_hat - b) d, of expected square
/// sigma^2 d^2 / S: d^2 / S in units of this frame's noise sigma^2, whatever sigma is. A still guide (d = 0)
/// leaves the blend's weight as it is; a guide that changed by as much as its neighbourhood's spread (an edge
/// that resampling moved, a light that went out) says the history it moved is as uncertain as this frame. No
/// constant but n's floor.
EMCV_FN float emcv_resolve_guide_weight(EMCV_IN(vec3) guide_change, EMCV_IN(vec3) guide_variance_sum, float n) {
    float weight = 0.0f;
    for (int c = 0; c < 3; ++c) {
        if (emcv_resolve_guide_shows_detail(guide_variance_sum[c], n)) {
            float d2 = guide_change[c] * guide_change[c];
            weight = max(weight, emcv_resolve_least_error_weight(d2 / guide_variance_sum[c]));
        }
    }
    return weight;
}

/// The reprojected history moved by the change of a noise-free guide: history + slope (guide - guide_history),
/// where `guide` is the guide at the pixel now and `guide_history` the last frame's guide resampled exactly as
/// the history was (the same position, kernel and texels). The guide is the image without what the resolve
/// averages (the renderer's: the unscattered diffuse light times the albedo, which has no samples). Resampling a
/// history shifts and blurs the detail it holds, and a light that changes moves it off this frame; the guide
/// undergoes the same resampling and the same change, exactly, so its difference is the history's error as far
/// as the history follows the guide's detail (slope, emcv_resolve_guide_slope). A still camera under still
/// lights has guide == guide_history: the history is unchanged.
EMCV_FN vec3 emcv_resolve_guided_history(EMCV_IN(vec3) history, EMCV_IN(vec3) slope, EMCV_IN(vec3) guide,
                                         EMCV_IN(vec3) guide_history) {
    EMCV_PRECISE vec3 moved = history + slope * (guide - guide_history);  // no FMA: the same bits on CPU and GPU
    return moved;
}

/// One resolve step: the clipped history blended with the current value, current weight `weight`.
EMCV_FN vec3 emcv_resolve_blend(EMCV_IN(vec3) clipped_history, EMCV_IN(vec3) current, float weight) {
    return mix(clipped_history, current, weight);
}

/// Whether a history texel stored at view depth `history_depth` shows the surface that was at view depth
/// `expected_depth` in the previous frame: the adaptive history's depth test (emcv_history_same_depth), where 0
/// marks a texel without history (the background, or none yet).
EMCV_FN bool emcv_resolve_same_surface(float history_depth, float expected_depth) {
    return history_depth > 0.0f && emcv_history_same_depth(history_depth, expected_depth);
}

EMCV_PORT_END

#endif  // EMCV_PORT_RESOLVE_H
