// SPDX-License-Identifier: MIT
// shaders/render/burley_taps.h — one pixel's Burley estimate over screen-space taps, for the two passes that take
// one: the burley pass (sss_burley.comp.glsl: N taps at a rotation that changes per pixel and frame, the
// stochastic estimate) and the resolve's guide (resolve.comp.glsl: EMCV_RESOLVE_GUIDE_TAPS taps at one fixed
// rotation, a noise-free estimate of the same scattered light). Every formula is from include/emcv/port/sss.h;
// docs/frame.md, "Burley SSS".
#ifndef EMCV_RENDER_BURLEY_TAPS_H
#define EMCV_RENDER_BURLEY_TAPS_H

#include "emcv/port/sss.h"
#include "render/gbuffer_read.h"

/// What every tap of pixel p needs: the per-channel shape distance at its material and albedo (d), the widest
/// channel the radii are drawn with, the pixel's view depth and the screen scale there.
struct EmcvBurleyPixel {
    vec3 albedo;  ///< the G-buffer's, read once for every use at the pixel
    vec3 d;
    float d_sample;
    float z;
    float pixels_per_mm;
};

/// The taps' setup at pixel p of scattering material `code`.
EmcvBurleyPixel emcv_render_burley_pixel(ivec2 p, uint code) {
    EmcvBurleyPixel px;
    px.albedo = texelFetch(gbuffer_albedo, p, 0).xyz;
    px.d = emcv_sss_shape_distance(materials[code - 1u].mean_free_path.xyz, px.albedo);
    px.d_sample = emcv_sss_widest(px.d);
    px.z = emcv_render_depth(p);
    px.pixels_per_mm = emcv_sss_pixels_per_mm(frame.projection.x, frame.viewport.x, px.z, frame.camera_position.w);
    return px;
}

/// Tap i of pixel p at `rotation` (emcv_sss_sample_uv): its per-channel weight w and the unscattered light l at the
/// pixel it lands on; false for a tap off screen or on a pixel that does not scatter (weight 0, docs/frame.md).
bool emcv_render_burley_tap(ivec2 p, EmcvBurleyPixel px, uint i, vec2 rotation, bool approximate, out vec3 w,
                            out vec3 l) {
    w = vec3(0.0f);
    l = vec3(0.0f);
#if defined(EMCV_BURLEY_SOBOL)  // burley-sobol-N (its row of the method table): scrambled Sobol' points
    vec2 u = emcv_sss_sample_uv_sobol(i, rotation);
#else
    vec2 u = emcv_sss_sample_uv(i, rotation);
#endif
    float r = emcv_sss_sample_radius(u.x, px.d_sample, approximate);
    vec2 offset = emcv_sss_offset_pixels(r, u.y, px.pixels_per_mm);
    ivec2 q = ivec2(floor(vec2(p) + 0.5f + offset));
    float zq = emcv_render_scattering_depth(q);
    if (zq == 0.0f) return false;
    float dz_mm = (zq - px.z) * frame.camera_position.w;
    w = emcv_sss_weight(r, emcv_sss_depth_aware_radius(r, dz_mm), px.d, px.d_sample);
    l = texelFetch(lit_diffuse, q, 0).xyz;
    return true;
}

/// The estimate sum(w l) / sum(w) per channel; a channel with no accepted tap keeps the unscattered value at p
/// (`centre`, the pixel's own irradiance).
vec3 emcv_render_burley_estimate(vec3 sum_wl, vec3 sum_w, vec3 centre) {
    return mix(centre, sum_wl / max(sum_w, vec3(1e-30f)), greaterThan(sum_w, vec3(0.0f)));
}

#endif  // #ifndef EMCV_RENDER_BURLEY_TAPS_H
