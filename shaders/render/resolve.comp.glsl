// SPDX-License-Identifier: MIT
// resolve: the temporal resolve after the composite (--resolve taa; docs/frame.md, "Temporal resolve"). It works on
// display values (after the tonemap and the sRGB encoding, before the 8-bit store), where a colour's error is what
// PSNR and a viewer see and where every value is bounded, so that one bright sample cannot hold the clip box open.
// Without jitter it filters the scattered light alone and adds the specular light back after (resolved_part). Per
// pixel: the current value and its 3x3 neighbourhood (one shared-memory tile with a one-pixel apron); last frame's
// resolved value at the reprojected position (motion vectors; Catmull-Rom over the 4x4 texels around it, as engines
// sample their history so that resampling it every frame does not blur it, each texel only where its stored view
// depth shows this surface, emcv_resolve_same_surface; less than half of the kernel's weight there: reset to the
// current value), clipped to the neighbourhood's box in YCoCg towards the current value filtered over its 3x3
// neighbours (emcv_resolve_filter_weight) with the detail the history's own 3x3 neighbourhood shows put back
// (emcv_resolve_target), and blended (include/emcv/port/resolve.h). Without jitter the box is first narrowed to
// this frame's own noise, which the SSS pass stores beside its estimate (emcv_resolve_narrow_to_noise): a history
// is kept only as far from this frame as its noise could take it, and a pixel nothing sampled shows this frame's
// value; where that noise is unknown the neighbourhood's box comes from the neighbours on the pixel's own surface
// (same_surface_moments). Without jitter the reprojected history is first moved by the change of a noise-free guide
// (a fixed-tap Burley estimate of the scattered light times the albedo, guide_scattered), resampled exactly as the
// history was, as far as the pixel's neighbourhood follows the guide's detail (emcv_resolve_guided_history): what
// resampling and a changing light did to the history, the guide shows without noise; where the guide changed by
// much of its 3x3 spread, the slope's noise makes that move uncertain, and the blend takes up this frame at the
// weight that uncertainty asks (emcv_resolve_guide_weight). The history keeps the resolved value and the pixel's
// view depth (0 for the background, which is never blended: it does not change), the guide texture this frame's
// guide.
#version 450 core

#include "emcv/port/resolve.h"
#include "emcv/port/sss.h"
#include "emcv/port/tonemap.h"
#include "render/burley_taps.h"
#include "render/gbuffer_read.h"

layout(local_size_x = EMCV_RENDER_TILE_SIZE, local_size_y = EMCV_RENDER_TILE_SIZE) in;

layout(EMCV_LAYOUT_BINDING(EMCV_RENDER_TEX_RESOLVE_CURRENT)) uniform sampler2D current_linear;
layout(EMCV_LAYOUT_BINDING(EMCV_RENDER_TEX_RESOLVE_HISTORY)) uniform sampler2D history_previous;
layout(rgba32f, EMCV_LAYOUT_IMAGE_BINDING(EMCV_RENDER_IMG_RESOLVE_HISTORY)) writeonly uniform image2D history_out;
layout(rgba8, EMCV_LAYOUT_IMAGE_BINDING(EMCV_RENDER_IMG_RESOLVED)) writeonly uniform image2D resolved_out;
layout(EMCV_LAYOUT_BINDING(EMCV_RENDER_TEX_RESOLVE_GUIDE)) uniform sampler2D guide_previous;
layout(rgba16f, EMCV_LAYOUT_IMAGE_BINDING(EMCV_RENDER_IMG_RESOLVE_GUIDE)) writeonly uniform image2D guide_out;

// This frame's SSS output, whose alpha holds its noise (emcv_sss_noise), and the samples each pixel took.
layout(EMCV_LAYOUT_BINDING(EMCV_RENDER_TEX_SSS_IN)) uniform sampler2D scattered_noise;
layout(EMCV_LAYOUT_BINDING(EMCV_RENDER_TEX_SSS_COUNT)) uniform usampler2D sample_counts;

#define APRON_SIDE (EMCV_RENDER_TILE_SIZE + 2)
shared vec3 tile_ycocg[APRON_SIDE * APRON_SIDE];
shared float tile_noise[APRON_SIDE * APRON_SIDE];
shared vec3 tile_guide[APRON_SIDE * APRON_SIDE];  // the guide (guide_part), where guided() holds

bool jitters() { return (frame.counters.w & EMCV_RENDER_FLAG_JITTER) != 0u; }

/// Whether the history follows the guide (EMCV_RESOLVE_GUIDE; not under jitter, where the history is meant to
/// hold the pixel's area, which this frame's point-sampled guide does not show).
bool guided() { return EMCV_RESOLVE_GUIDE != 0 && !jitters(); }

/// The part of the composite at q (clamped to the screen) that the resolve filters, linear: without jitter the
/// scattered light alone, the composite less its specular radiance. The specular light of the scene's lights is
/// computed, not sampled: it has no noise to average, and under a moving camera it moves over the surface, so
/// a history of it lags the view (on the orbiting skin close-up the resolve lost 12 dB to that lag). Under
/// jitter the resolve also anti-aliases, which the whole image needs, specular edges included.
vec3 resolved_part(ivec2 q) {
    q = clamp(q, ivec2(0), ivec2(frame.viewport.xy) - 1);
    vec3 linear = texelFetch(current_linear, q, 0).xyz;
    if (!jitters()) linear -= texelFetch(lit_specular, q, 0).xyz;
    return linear;
}

/// This frame's noise code at q (clamped to the screen; emcv_sss_noise): what the stochastic SSS pass stored at
/// a pixel that scatters, exact everywhere else and for every pixel when no such pass ran (diffuse, separable:
/// nothing in the image is sampled).
float noise_at(ivec2 q) {
    q = clamp(q, ivec2(0), ivec2(frame.viewport.xy) - 1);
    if ((frame.counters.w & EMCV_RENDER_FLAG_SSS_NOISE) == 0u || !emcv_render_scatters(emcv_render_material_code(q)))
        return emcv_sss_noise_exact();
    return texelFetch(scattered_noise, q, 0).w;
}

/// The YCoCg half-widths of the noise box at p (tile position `local`): EMCV_RESOLVE_NOISE_SIGMA standard
/// deviations of this frame's estimate, from p's own per-sample variance and its 3x3 neighbours'
/// (emcv_resolve_pooled_noise) over p's samples, scaled by the albedo (the composite multiplies the scattered
/// light by it) and carried through the display encoding at the current value, upwards and downwards (the larger
/// of the two per channel). False where no box applies
/// (p's own noise unknown).
bool noise_extent(ivec2 p, ivec2 local, vec3 current, out vec3 extent) {
    extent = vec3(0.0f);
    float own = tile_noise[local.x + local.y * APRON_SIDE];
    float variance = 0.0f;
    if (own != emcv_sss_noise_exact()) {
        float sum = 0.0f, known = 0.0f;
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                float v = tile_noise[(local.x + dx) + (local.y + dy) * APRON_SIDE];
                if (v >= 0.0f) {
                    sum += v;
                    known += 1.0f;
                }
            }
        }
        variance = emcv_resolve_pooled_noise(own, sum, known, texelFetch(sample_counts, p, 0).x);
        if (variance < 0.0f) return false;
    }
    if (variance == 0.0f) return true;  // exact: the box closes on the current value
    vec3 deviation = float(EMCV_RESOLVE_NOISE_SIGMA) * sqrt(variance) * texelFetch(gbuffer_albedo, p, 0).xyz;
    // Carried through the display encoding both ways (emcv_resolve_noise_extent); the current value's encoding is
    // the tile's (current, in YCoCg): one encoding per pixel for it, not two.
    float exposure = frame.background.w;
    extent = emcv_resolve_noise_extent(resolved_part(p) * exposure, emcv_ycocg_to_rgb(current), deviation * exposure,
                                       int(frame.ambient.w));
    return true;
}

/// The sums of the display values (YCoCg) and of their squares over p's 3x3 neighbours (tile position `local`)
/// that show p's own surface (the same material, and a view depth within the adaptive history's tolerance of
/// p's, emcv_history_same_depth), p among them; returns their count. The box of a pixel whose noise this frame
/// cannot tell (emcv_sss_noise_unknown: fewer than two effective samples, as on a thin object's edge, whose
/// samples mostly land off it) comes from these alone: another surface beside it (a lit floor behind a slab's
/// edge) says nothing of what this pixel shows, and its values widened the box until it held the history of a
/// light that had gone off (docs/frame.md, "The noise box").
float same_surface_moments(ivec2 p, ivec2 local, float depth, out vec3 sum, out vec3 sum_squares) {
    sum = vec3(0.0f);
    sum_squares = vec3(0.0f);
    float count = 0.0f;
    uint code = emcv_render_material_code(p);
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = p + ivec2(dx, dy);
            if (!emcv_render_on_screen(q) || emcv_render_material_code(q) != code ||
                !emcv_history_same_depth(emcv_render_depth(q), depth))
                continue;
            vec3 v = tile_ycocg[(local.x + dx) + (local.y + dy) * APRON_SIDE];
            sum += v;
            sum_squares += v * v;
            count += 1.0f;
        }
    }
    return count;
}

/// A linear colour as the display shows it, in YCoCg.
vec3 display_ycocg(vec3 linear) {
    return emcv_rgb_to_ycocg(emcv_display_encode(linear * frame.background.w, int(frame.ambient.w)));
}

/// The scattered light the guide shows at scattering pixel q (material `code`): a Burley estimate of
/// EMCV_RESOLVE_GUIDE_TAPS taps at one fixed rotation (render/burley_taps.h, the burley pass's taps), the same taps
/// every frame, so that it has no frame-to-frame noise; with no taps, the unscattered light.
vec3 guide_scattered(ivec2 q, uint code) {
    vec3 centre = texelFetch(lit_diffuse, q, 0).xyz;
    if (EMCV_RESOLVE_GUIDE_TAPS == 0) return centre;
    EmcvBurleyPixel px = emcv_render_burley_pixel(q, code);
    bool approximate = (frame.counters.w & EMCV_RENDER_FLAG_APPROXIMATE_CDF) != 0u;
    vec3 sum_w = vec3(0.0f), sum_wl = vec3(0.0f);
    for (uint i = 0u; i < uint(EMCV_RESOLVE_GUIDE_TAPS); ++i) {
        vec3 w, l;
        if (!emcv_render_burley_tap(q, px, i, vec2(0.5f), approximate, w, l)) continue;
        sum_w += w;
        sum_wl += w * l;
    }
    return emcv_render_burley_estimate(sum_wl, sum_w, centre);
}

/// The guide at q (clamped to the screen): the resolved part without the SSS pass's sampling, in display YCoCg
/// (`resolved`: display_ycocg of resolved_part(q)). At a pixel that scatters, the albedo times the scattered light
/// as a fixed estimate gives it (guide_scattered: no noise from frame to frame); elsewhere the resolved part. Each
/// value is rounded to binary16 here, so that the guide texture stores it exactly (llvmpipe's binary16 store
/// truncates; hardware rounds) and a guide that did not change reads back equal to this frame's.
vec3 guide_part(ivec2 q, vec3 resolved) {
    q = clamp(q, ivec2(0), ivec2(frame.viewport.xy) - 1);
    vec3 guide = resolved;
    uint code = emcv_render_material_code(q);
    if (emcv_render_scatters(code))
        guide = display_ycocg(texelFetch(gbuffer_albedo, q, 0).xyz * guide_scattered(q, code));
    return vec3(unpackHalf2x16(packHalf2x16(guide.xy)), unpackHalf2x16(packHalf2x16(vec2(guide.z, 0.0f))).x);
}

/// The guide slope at the tile position `local` (emcv_resolve_guide_slope) over its 3x3 neighbourhood, and the
/// guide's centred sum of squares there (`guide_variance_sum`, for emcv_resolve_guide_weight).
vec3 guide_slope(ivec2 local, out vec3 guide_variance_sum) {
    vec3 guide_mean = vec3(0.0f), value_mean = vec3(0.0f);
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            uint i = uint((local.x + dx) + (local.y + dy) * APRON_SIDE);
            guide_mean += tile_guide[i];
            value_mean += tile_ycocg[i];
        }
    }
    guide_mean /= 9.0f;
    value_mean /= 9.0f;
    vec3 covariance_sum = vec3(0.0f);
    guide_variance_sum = vec3(0.0f);
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            uint i = uint((local.x + dx) + (local.y + dy) * APRON_SIDE);
            vec3 g = tile_guide[i] - guide_mean;
            guide_variance_sum += g * g;
            covariance_sum += g * (tile_ycocg[i] - value_mean);
        }
    }
    return emcv_resolve_guide_slope(guide_variance_sum, covariance_sum, 9.0f);
}

/// Under the camera's jitter (EMCV_RENDER_FLAG_JITTER) a pixel on a silhouette shows the object on some frames
/// and what lies behind it on others, and its history rightly holds their mix: there a history texel is of this
/// pixel when its stored depth is that of any surface the pixel's 3x3 neighbourhood shows now (each at its
/// previous depth; the background, depth 0, matches the background), so that only a surface the neighbourhood
/// no longer shows (a disocclusion) restarts it. Without jitter a texel must show this pixel's own surface.
shared float tile_previous_depth[APRON_SIDE * APRON_SIDE];

/// The depth the surface at q had in the previous frame (0 for the background and off screen).
float previous_depth_at(ivec2 q) {
    if (!emcv_render_on_screen(q)) return 0.0f;
    float z = emcv_render_depth(q);
    return z > 0.0f ? emcv_render_previous_depth(q, z) : 0.0f;
}

/// Whether a history texel of stored depth `history_depth` shows a surface pixel p (tile position `local`) shows.
bool history_of_pixel(float history_depth, float expected_depth, ivec2 local) {
    if (!jitters()) return emcv_resolve_same_surface(history_depth, expected_depth);
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            float z = tile_previous_depth[(local.x + dx) + (local.y + dy) * APRON_SIDE];
            if (z > 0.0f ? emcv_resolve_same_surface(history_depth, z) : history_depth == 0.0f) return true;
        }
    }
    return false;
}

/// Last frame's resolved value (YCoCg) at this surface's previous position, or false where none shows it; and
/// the variance of the history's own 3x3 neighbourhood there (the texels around the one the position falls
/// nearest, among the 4x4 the resampling reads, each where it shows this surface): the detail the clip's target
/// keeps (emcv_resolve_target); and that neighbourhood's mean, where all 9 texels show this surface (else
/// `history_mean_known` is false); and, where guided(), last frame's guide resampled with the same weights over the
/// same texels (`guide_history`).
bool reprojected_history(ivec2 p, float depth, ivec2 local, out vec3 history, out vec3 history_variance,
                         out vec3 history_mean, out bool history_mean_known, out vec3 guide_history) {
    history = vec3(0.0f);
    guide_history = vec3(0.0f);
    history_variance = vec3(0.0f);
    history_mean = vec3(0.0f);
    history_mean_known = false;
    float expected_depth = emcv_render_previous_depth(p, depth);
    // The previous position of p's centre, in texel-centre coordinates (between four texel centres).
    vec2 previous = emcv_render_previous_position(p) - 0.5f;
    ivec2 base = ivec2(floor(previous));
    vec2 t = previous - vec2(base);
    ivec2 nearest = base + ivec2(greaterThanEqual(t, vec2(0.5f)));
    vec4 wx = emcv_resolve_catmull_rom(t.x), wy = emcv_resolve_catmull_rom(t.y);
    float weight_sum = 0.0f;
    vec3 near_sum = vec3(0.0f), near_sum_squares = vec3(0.0f);
    float near_count = 0.0f;
    for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) {
            float w = wx[i] * wy[j];
            ivec2 q = base + ivec2(i - 1, j - 1);
            bool near = all(lessThanEqual(abs(q - nearest), ivec2(1)));
            if ((w == 0.0f && !near) || !emcv_render_on_screen(q)) continue;
            vec4 texel = texelFetch(history_previous, q, 0);
            if (!history_of_pixel(texel.w, expected_depth, local)) continue;
            if (w != 0.0f) {
                history += w * texel.xyz;
                if (guided()) guide_history += w * texelFetch(guide_previous, q, 0).xyz;
                weight_sum += w;
            }
            if (near) {
                near_sum += texel.xyz;
                near_sum_squares += texel.xyz * texel.xyz;
                near_count += 1.0f;
            }
        }
    }
    // Too little of the kernel's weight on this surface (a disocclusion, or only negative lobes): no history.
    if (!(weight_sum > 0.5f)) return false;
    history /= weight_sum;
    guide_history /= weight_sum;
    if (near_count > 0.0f) history_variance = emcv_resolve_variance(near_sum, near_sum_squares, near_count);
    history_mean_known = near_count == 9.0f;
    if (history_mean_known) history_mean = near_sum / 9.0f;
    return true;
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 origin = ivec2(gl_WorkGroupID.xy) * EMCV_RENDER_TILE_SIZE - 1;
    for (uint i = gl_LocalInvocationIndex; i < uint(APRON_SIDE * APRON_SIDE); i += uint(EMCV_RENDER_TILE_SIZE * EMCV_RENDER_TILE_SIZE)) {
        ivec2 q = origin + ivec2(int(i) % APRON_SIDE, int(i) / APRON_SIDE);
        tile_ycocg[i] = display_ycocg(resolved_part(q));
        if (guided()) tile_guide[i] = guide_part(q, tile_ycocg[i]);
        if (!jitters()) tile_noise[i] = noise_at(q);
        if (jitters()) tile_previous_depth[i] = previous_depth_at(q);
    }
    barrier();
    if (!emcv_render_on_screen(p)) return;

    ivec2 local = ivec2(gl_LocalInvocationID.xy) + 1;
    vec3 current = tile_ycocg[local.x + local.y * APRON_SIDE];
    float depth = emcv_render_depth(p);
    vec3 resolved = current;
    vec3 history, history_variance, history_mean, guide_history;
    bool history_mean_known;
    // The background is blended only under jitter (its silhouette pixels mix with the object's); without
    // jitter it does not change and is shown as it is.
    if ((depth > 0.0f || jitters()) &&
        reprojected_history(p, depth, local, history, history_variance, history_mean, history_mean_known,
                            guide_history)) {
        // The history moved by the guide's change, and the weight that change's uncertainty asks of the blend
        // (emcv_resolve_guide_weight; 0 where the guide did not change).
        float guide_weight = 0.0f;
        if (guided()) {
            vec3 guide = tile_guide[local.x + local.y * APRON_SIDE], guide_variance_sum;
            vec3 slope = guide_slope(local, guide_variance_sum);
            history = emcv_resolve_guided_history(history, slope, guide, guide_history);
            guide_weight = emcv_resolve_guide_weight(guide - guide_history, guide_variance_sum, 9.0f);
        }
        vec3 sum = vec3(0.0f), sum_squares = vec3(0.0f), filtered = vec3(0.0f);
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                vec3 v = tile_ycocg[(local.x + dx) + (local.y + dy) * APRON_SIDE];
                sum += v;
                sum_squares += v * v;
                filtered += emcv_resolve_filter_weight(dx, dy) * v;
            }
        }
        // Without jitter the box is also narrowed to this frame's own noise: under jitter the history also
        // anti-aliases, a difference from this frame that the SSS pass's noise does not measure.
        vec3 extent;
        bool noise_box = !jitters() && noise_extent(p, local, current, extent);
        vec3 lo, hi;
        if (!jitters() && !noise_box) {
            // This frame's noise is unknown here (noise_extent): the box is its own surface's neighbours'.
            vec3 same_sum, same_sum_squares;
            float same_count = same_surface_moments(p, local, depth, same_sum, same_sum_squares);
            emcv_resolve_clip_box(same_sum, same_sum_squares, same_count, current, lo, hi);
        } else {
            emcv_resolve_clip_box(sum, sum_squares, 9.0f, current, lo, hi);
        }
        if (noise_box) emcv_resolve_narrow_to_noise(current, extent, lo, hi);
        vec3 spread = emcv_resolve_variance(sum, sum_squares, 9.0f);
        vec3 detailed = emcv_resolve_target(current, filtered, spread, history_variance);
        vec3 target = emcv_resolve_clip(detailed, current, lo, hi);
        // A history beyond the noise box is wrong, not noisy: what the clip keeps of it is taken up at the weight
        // that minimises the error of mixing it with this frame (emcv_resolve_current_weight); so is a history
        // whose neighbourhood has moved off this frame's by more than the noise of a 9-value mean
        // (emcv_resolve_shift_weight: a slow fade, a resampled history).
        float weight = noise_box ? emcv_resolve_current_weight(history, current, extent) : float(EMCV_RESOLVE_BLEND);
        if (noise_box && history_mean_known)
            weight = max(weight, emcv_resolve_shift_weight(sum / 9.0f - history_mean, extent, 9.0f));
        // So is a history the guide moved by as much as the guide's own spread (emcv_resolve_guide_weight).
        if (noise_box) weight = max(weight, guide_weight);
        resolved = emcv_resolve_blend(emcv_resolve_clip(history, target, lo, hi), current, weight);
    }
    imageStore(history_out, p, vec4(resolved, depth));
    if (guided()) imageStore(guide_out, p, vec4(tile_guide[local.x + local.y * APRON_SIDE], 0.0f));
    vec3 shown = emcv_ycocg_to_rgb(resolved);
    // The specular light added back to the resolved scattered light where it was taken out, in linear (through
    // the display's inverse: adding it in display space would carry this frame's noise through the tonemap's
    // curvature).
    if (!jitters()) {
        int tonemap = int(frame.ambient.w);
        vec3 specular = texelFetch(lit_specular, p, 0).xyz * frame.background.w;
        shown = emcv_display_encode(emcv_display_decode(shown, tonemap) + specular, tonemap);
    }
    imageStore(resolved_out, p, vec4(clamp(shown, 0.0f, 1.0f), 1.0f));
}
