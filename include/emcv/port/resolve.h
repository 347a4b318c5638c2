// SPDX-License-Identifier: MIT
/// \file
/// emcv/port/resolve.h — the per-pixel maths of a temporal resolve (TAA without jitter) after the SSS, as
/// engines resolve a stochastic SSS before display: the history, reprojected with the motion vectors, is clipped
/// to the current frame's 3x3 neighbourhood in YCoCg (variance clipping) and blended exponentially with the
/// current pixel. The demo's `resolve` pass (shaders/render/resolve.comp.glsl) runs it; docs/frame.md,
/// "Temporal resolve", states the choices and their sources.
//
// TUNABLES   EMCV_RESOLVE_BLEND ........ weight of the current frame in the blend, (0, 1]; default 0.1
//            EMCV_RESOLVE_CLIP_SIGMA ... half-width of the clip box in neighbourhood standard deviations,
//                                        (0, 4]; default 1
//            EMCV_RESOLVE_NOISE_SIGMAS . half-width of the temporal noise box in the pixel's own temporal
//                                        deviations, [0, 6]; default 3 (0: the neighbourhood's box alone)
#ifndef EMCV_PORT_RESOLVE_H
#define EMCV_PORT_RESOLVE_H

#include "history.h"
#include "port.h"

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

/// Half-width of the temporal noise box around the current value, in the pixel's own temporal standard deviations
/// (emcv_resolve_noise_box): three, so that a converged history lies inside it on all but 0.3% of the frames of a
/// Gaussian noise (the two-sided 3-sigma bound) and only a change beyond the pixel's own noise is clipped by it.
/// Range [0, 6]; 0 leaves the neighbourhood's box alone (the resolve without it, bit for bit).
#ifndef EMCV_RESOLVE_NOISE_SIGMAS
#define EMCV_RESOLVE_NOISE_SIGMAS 3.0f
#endif

EMCV_PORT_BEGIN

/// RGB to YCoCg (luma, orange and green chroma): an exact, invertible basis in which a box around the
/// neighbourhood follows its luma and its hue separately.
EMCV_FN vec3 emcv_rgb_to_ycocg(EMCV_IN(vec3) c) {
    return vec3(0.25f * c.x + 0.5f * c.y + 0.25f * c.z, 0.5f * c.x - 0.5f * c.z, -0.25f * c.x + 0.5f * c.y - 0.25f * c.z);
}

/// The inverse of emcv_rgb_to_ycocg.
EMCV_FN vec3 emcv_ycocg_to_rgb(EMCV_IN(vec3) c) {
    return vec3(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z);
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
    vec3 deviation = sqrt(max(sum_squares / n - mean * mean, vec3(0.0f)));
    lo = min(mean - float(EMCV_RESOLVE_CLIP_SIGMA) * deviation, current);
    hi = max(mean + float(EMCV_RESOLVE_CLIP_SIGMA) * deviation, current);
}

/// The history moved along the line towards `target`, a colour inside the box [lo, hi], until it lies in the box
/// (a clip, not a per-channel clamp): the clipped colour is a mix of the history and the target, never a hue
/// that neither holds. The resolve's target is the pixel's current value filtered over its 3x3 neighbourhood
/// (emcv_resolve_filter_weight), itself clipped towards the current value into the box: an estimate of what
/// this frame shows at the pixel with less noise than the pixel alone. Clipping towards the box's centre, the
/// neighbourhood's plain mean, pulls edges and relief towards their neighbours' average, a blur the next frames
/// keep; towards the raw current value, it keeps more of that value's noise (both measured, docs/frame.md
/// "Temporal resolve"). Inside the box the history is kept unchanged. The box is at least half an 8-bit display
/// step wide on every side: a flat channel (zero spread) would otherwise clip the history's rounding error and
/// pull a still pixel off its value, by differences the display cannot show.
EMCV_FN float emcv_resolve_clip_fraction(EMCV_IN(vec3) history, EMCV_IN(vec3) target, EMCV_IN(vec3) lo,
                                         EMCV_IN(vec3) hi) {
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
    return max(t, 0.0f);
}

/// The history clipped into the box towards `target` (emcv_resolve_clip_fraction's t along history - target).
EMCV_FN vec3 emcv_resolve_clip(EMCV_IN(vec3) history, EMCV_IN(vec3) target, EMCV_IN(vec3) lo, EMCV_IN(vec3) hi) {
    return target + emcv_resolve_clip_fraction(history, target, lo, hi) * (history - target);
}

/// The weight of the neighbour at (dx, dy), each in {-1, 0, 1}, in the 3x3 filter of the clip's target: the
/// binomial (1 2 1) x (1 2 1) / 16, the smallest separable low-pass that keeps the pixel itself the heaviest tap
/// (a Gaussian of about 0.7 px, as engines filter the current frame for their clip).
EMCV_FN float emcv_resolve_filter_weight(int dx, int dy) {
    return float((2 - abs(dx)) * (2 - abs(dy))) * 0.0625f;
}

// The temporal noise state of a pixel (a vec4 beside its resolved value), every entry an exponential average at the
// blend's weight (the history's own memory) of what the resolve saw at the pixel while it kept its history:
//   x  the variance of its current luma around the kept history (YCoCg's Y),
//   y  the same for its chroma (the mean of Co's and Cg's),
//   z  the luma offset of its filtered current value from its history (a pixel on a ridge sits above its
//      filtered value for good; what moves that offset is a change),
//   w  the mean of its current luma's difference from its history (zero-mean noise averages out; a change that
//      the history lags behind, such as a slow fade, does not).
// x, y and z are 0 where nothing is measured yet (a new history, or one restarted by a change); w is 0 only in a
// new history.

/// The clip box grown to hold the current value -+ EMCV_RESOLVE_NOISE_SIGMAS of the pixel's temporal standard
/// deviations (the noise state's luma and chroma variances; 0 leaves the box as it is). The neighbourhood's box
/// measures the spread of nine different pixels, detail as well as noise: a pixel that stands above its neighbours
/// (a ridge, a highlight, skin's relief) has a converged history beyond that box on every frame whose noise falls
/// inwards, and clipping it there pulls the pixel towards its neighbours, a blur the history keeps (docs/frame.md,
/// "Temporal resolve"). The pixel's own temporal spread is its noise alone while nothing changes, and a history
/// within a few of its deviations of the current value is one the noise cannot tell from it.
EMCV_FN void emcv_resolve_noise_box(EMCV_IN(vec3) current, EMCV_IN(vec4) state, EMCV_INOUT(vec3) lo,
                                    EMCV_INOUT(vec3) hi) {
    vec3 half_width = float(EMCV_RESOLVE_NOISE_SIGMAS) * sqrt(max(vec3(state.x, state.y, state.y), vec3(0.0f)));
    lo = min(lo, current - half_width);
    hi = max(hi, current + half_width);
}

/// This frame's moves against the reprojected history, luma: x the filtered current value's, y the current
/// value's (what emcv_resolve_history_changed tests and emcv_resolve_noise_update averages).
EMCV_FN vec2 emcv_resolve_moves(EMCV_IN(vec3) filtered, EMCV_IN(vec3) current, EMCV_IN(vec3) history) {
    return vec2(filtered.x - history.x, current.x - history.x);
}

/// Whether the history no longer shows what the pixel's noise scatters around (a light change): either the
/// filtered move (`moves`.x) is off the offset the state has learnt by more than EMCV_RESOLVE_NOISE_SIGMAS of its
/// deviation, or the mean of the pixel's moves, with this frame's taken in, is further from 0 than that many
/// deviations of such a mean. A change below one pixel's noise moves its whole neighbourhood the same way, and
/// the filter averages their noise down: the filtered value's variance is the sum of the squared filter weights
/// (9 / 64) times a pixel's, the history's weight / (2 - weight) of it (an exponential average of independent
/// frames), and a mean of the moves at most that (the bound for independent moves; moves against a history that
/// follows them are anticorrelated and average out faster). A slow change (a fade) moves the pixel a
/// little every frame and the history lags behind it by the same amount every frame: the mean of its moves then
/// stays off 0 where noise would average out. Both from the tracked luma variance (one pixel's noise taken for
/// its neighbours'). False where no variance is measured yet (the neighbourhood's box decides).
EMCV_FN bool emcv_resolve_history_changed(EMCV_IN(vec2) moves, EMCV_IN(vec4) state, float weight) {
    if (!(state.x > 0.0f)) return false;
    float filter_gain = 0.0f;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) filter_gain += emcv_resolve_filter_weight(dx, dy) * emcv_resolve_filter_weight(dx, dy);
    float average_gain = weight / (2.0f - weight);
    float k = float(EMCV_RESOLVE_NOISE_SIGMAS);
    bool neighbourhood_moved = abs(moves.x - state.z) > k * sqrt((filter_gain + average_gain) * state.x);
    bool mean_moved = abs(mix(state.w, moves.y, weight)) > k * sqrt(average_gain * state.x);
    return neighbourhood_moved || mean_moved;
}

/// The noise state after this frame. Where the history changed (emcv_resolve_history_changed) the variances and
/// the offset restart at 0, so that a change never widens the box that would then keep the old image: the box is
/// the neighbourhood's alone until the pixel's noise is measured again. The mean of the moves carries on through
/// a restart: a fade goes on moving the pixel, and its evidence must keep the box closed while it lasts. Where the
/// clip moved the history (`clip_fraction` < 1: a noise outlier, or a pixel whose box the noise does not yet
/// widen) the state is kept as it was: the move of a clipped history is not the pixel's noise, and restarting there
/// would hold a pixel that stands out of its neighbourhood at the neighbourhood's box for good. Otherwise the
/// averages take in this frame: the squared differences of the current value and the kept history, the filtered
/// move and the pixel's move. A state with nothing measured takes this frame's squares and filtered move as they
/// are (one frame's unbiased estimate: an average started from 0 would read the noise as far smaller than it is
/// for its first frames, and the moves' mean against it as a change).
EMCV_FN vec4 emcv_resolve_noise_update(EMCV_IN(vec4) state, EMCV_IN(vec3) current, EMCV_IN(vec3) kept_history,
                                       float clip_fraction, EMCV_IN(vec2) moves, bool changed, float weight) {
    float drift = mix(state.w, moves.y, weight);
    if (changed) return vec4(0.0f, 0.0f, 0.0f, drift);
    if (clip_fraction < 1.0f) return state;
    vec3 d = current - kept_history;
    vec2 variances = vec2(d.x * d.x, 0.5f * (d.y * d.y + d.z * d.z));
    if (!(state.x > 0.0f)) return vec4(variances.x, variances.y, moves.x, drift);
    return vec4(mix(state.x, variances.x, weight), mix(state.y, variances.y, weight), mix(state.z, moves.x, weight),
                drift);
}

/// The Catmull-Rom weights of the four texels around a sample at fraction t in [0, 1) past the second texel
/// (texels at -1, 0, 1, 2): the cubic that interpolates them with continuous slope, sharp enough that resampling
/// a moving history every frame does not blur it as bilinear weights do. They sum to 1; t = 0 gives (0, 1, 0, 0).
EMCV_FN vec4 emcv_resolve_catmull_rom(float t) {
    return vec4(t * (-0.5f + t * (1.0f - 0.5f * t)), 1.0f + t * t * (-2.5f + 1.5f * t), t * (0.5f + t * (2.0f - 1.5f * t)),
                t * t * (-0.5f + 0.5f * t));
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
