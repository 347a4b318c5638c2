// SPDX-License-Identifier: MIT
// shaders/reference/port_reference.glsl — the reference kernel of the installed HLSL (share/emcv/
// emcv_port_reference.hlsl): the body of a compute shader that goes after `#version 450 core` and the flattened
// port (emcv_port.glsl), as an engine's would (cmake/emcv_port_hlsl.cmake assembles and translates it).
// It binds what a GPU engine binds for the adaptive SSS methods, buffers and textures in set 0 and images in
// set 1 (EMCV_LAYOUT_BINDING / EMCV_LAYOUT_IMAGE_BINDING), and calls every port function once, so that
// spirv-cross's translation holds each of them as an HLSL function of the same name. One invocation per pixel:
// decode the cv and spvg histories, pool, plan the count, sample Burley radii, push, bin sigma for the
// budget, encode, tonemap, resolve. Not one of the renderer's passes (shaders/adaptive, shaders/render).

layout(local_size_x = EMCV_WORKGROUP_SIZE_X) in;

// set 0: storage buffers, a uniform block and a texture (binding numbers unique across these types)
layout(std430, EMCV_LAYOUT_BINDING(0)) readonly buffer Irradiance { float irradiance[]; } irradiance_in;
layout(std430, EMCV_LAYOUT_BINDING(1)) buffer Covariance { EmcvEmcm2 state[]; } covariance;   // cv, per pixel
layout(std430, EMCV_LAYOUT_BINDING(2)) buffer Residual { EmcvMovingStats state[]; } residual;  // spvg, per pixel
layout(std430, EMCV_LAYOUT_BINDING(3)) buffer Budget { EmcvBudgetBlock block; } budget;       // budget.h
layout(std140, EMCV_LAYOUT_BINDING(4)) uniform Frame {
    uvec4 frame_seed_width_height;  // (frame, seed, width, height)
    vec4 camera;                    // (P00, viewport width, mm per world unit, view depth)
} frame;
layout(EMCV_LAYOUT_BINDING(5)) uniform sampler2D albedo_map;
// set 1: images (OpenGL image units 0..7)
layout(rgba32f, EMCV_LAYOUT_IMAGE_BINDING(0)) uniform image2D history_cov;    // (C_ff, C_fG, C_GG, count)
layout(rg32f, EMCV_LAYOUT_IMAGE_BINDING(1)) uniform image2D history_means;    // (mean_f, mean_G)
layout(rgba16f, EMCV_LAYOUT_IMAGE_BINDING(2)) uniform image2D history_stats;  // spvg: (mean, var / unit, count, 0)
layout(r32ui, EMCV_LAYOUT_IMAGE_BINDING(3)) uniform uimage2D sample_count;
layout(rgba8, EMCV_LAYOUT_IMAGE_BINDING(4)) uniform image2D display;

void main() {
    const uint width = frame.frame_seed_width_height.z;
    const uint height = frame.frame_seed_width_height.w;
    const uvec2 pixel = gl_GlobalInvocationID.xy;
    if (pixel.x >= width || pixel.y >= height) return;
    const uint index = pixel.y * width + pixel.x;
    const uint frame_index = frame.frame_seed_width_height.x;
    const uint seed = frame.frame_seed_width_height.y;
    const ivec2 texel = ivec2(pixel);

    // The histories: cv's EMCM in two images, spvg's moving stats in one (history.h).
    EmcvEmcm2 cov;
    if (!emcv_history_decode_emcm2(imageLoad(history_cov, texel), imageLoad(history_means, texel).xy, cov) ||
        !emcv_history_reusable(1u, 1u, frame.camera.w, frame.camera.w, vec3(0.0f, 0.0f, 1.0f), vec3(0.0f, 0.0f, 1.0f)))
        cov = emcv_emcm2_init();
    EmcvMovingStats stats;
    if (!emcv_history_decode_stats(imageLoad(history_stats, texel), stats) || !emcv_moving_stats_valid(stats))
        stats = emcv_moving_stats_init();
    if (!emcv_emcm2_valid(cov)) cov = covariance.state[index];

    // Plan: the per-sample variance, pooled with the pixel itself, and the count under the tunables.
    float sigma2 = emcv_history_sigma2_cv(cov, EMCV_HISTORY_ETA_EMCM);
    float pooled = 0.0f;
    uint pooled_count = 0u;
    emcv_history_pool_add(pooled, pooled_count, sigma2);
    emcv_history_pool_add(pooled, pooled_count, emcv_history_sigma2_moving(stats, EMCV_HISTORY_ETA_MOVING));
    sigma2 = emcv_history_pool_sigma2(sigma2, pooled, pooled_count);
    // The budget's shrinkage towards last frame's prior (history.h): the pool's effective frames, the frame
    // statistics this pixel adds (raw histogram, moments, 1 / K), and the shrunk variance.
    float inverse_frames = 0.0f;
    const float own_frames = emcv_history_effective_frames(cov.count, EMCV_HISTORY_ETA_EMCM);
    emcv_history_pool_add_frames(inverse_frames, sigma2, own_frames);
    const float frames = emcv_history_pool_frames(pooled_count, inverse_frames);
    if (sigma2 >= 0.0f && frames > 0.0f) {
        atomicAdd(budget.block.raw_count[emcv_budget_bin(sqrt(sigma2))], 1u);
        atomicAdd(budget.block.raw_inverse_frames, emcv_history_inverse_frames_units(frames));
    }
    const vec3 moments = emcv_history_moments_add(vec3(0.0f), emcv_budget_bin(sqrt(max(sigma2, 0.0f))), 1u);
    const vec2 prior = emcv_history_frame_prior(moments, emcv_history_inverse_frames_units(max(frames, 1.0f)),
                                                emcv_history_spend_relative_variance());
    if (index == 0u) {  // what a solve stores for the next frame
        budget.block.mean_sigma2 = prior.x;
        budget.block.between_variance = prior.y;
    }
    sigma2 = emcv_history_shrink_sigma2(sigma2, frames, budget.block.mean_sigma2, budget.block.between_variance,
                                        emcv_history_spend_relative_variance());
    const float u_round = emcv_budget_u(pixel.x, pixel.y, frame_index, seed);
    int n = emcv_history_budget_mode() ? emcv_history_count_spend(sigma2, budget.block.lambda, u_round)
                                       : emcv_history_count_target(sigma2);
    n = max(n, emcv_history_count_quality(sigma2, EMCV_HISTORY_TARGET, EMCV_HISTORY_N_MIN, EMCV_HISTORY_N_MAX) -
                   emcv_history_count_budget(sigma2, budget.block.lambda, EMCV_HISTORY_SPP_BUDGET,
                                             EMCV_HISTORY_N_MIN, EMCV_HISTORY_N_MAX, u_round));

    // Scatter: Burley radii around the pixel against its unscattered irradiance G.
    const vec3 albedo = texelFetch(albedo_map, texel, 0).rgb;
    const vec3 d = emcv_sss_shape_distance(vec3(1.0f, 0.5f, 0.25f), albedo);
    const float d_max = emcv_sss_widest(d);
    const float px_per_mm = emcv_sss_pixels_per_mm(frame.camera.x, frame.camera.y, frame.camera.w, frame.camera.z);
    const bool sub_pixel = emcv_history_sub_pixel(d_max, px_per_mm);
    const vec2 rotation = emcv_sss_rotation(pixel.x, pixel.y, frame_index, seed);
    const float g = irradiance_in.irradiance[index];
    vec3 sum = vec3(0.0f);
    vec3 weights = vec3(0.0f);
    vec3 weights2 = vec3(0.0f), weights2_values = vec3(0.0f), weights2_squares = vec3(0.0f);  // emcv_sss_noise's sums
    for (int i = 0; i < n && !sub_pixel; ++i) {
        const vec2 u = emcv_sss_sample_uv(uint(i), rotation);
        const float r = emcv_sss_sample_radius(u.x, d_max, (i & 1) == 1);
        const vec2 offset = emcv_sss_offset_pixels(r, u.y, px_per_mm);
        const uint x = uint(clamp(int(pixel.x) + int(round(offset.x)), 0, int(width) - 1));
        const vec3 w = emcv_sss_weight(r, emcv_sss_depth_aware_radius(r, 0.0f), d, d_max);
        const float value = irradiance_in.irradiance[pixel.y * width + x];
        sum += w * value;
        weights += w;
        weights2 += w * w;
        weights2_values += w * w * value;
        weights2_squares += w * w * (value * value);
    }
    const vec3 scattered = sub_pixel ? vec3(g) : sum / max(weights, vec3(emcv_float_min_normal()));
    // This frame's noise of the estimate (sss.h), which the resolve below narrows its box to.
    const float noise = emcv_sss_noise(weights, weights2, weights2_values, weights2_squares, scattered,
                                       uint(sub_pixel ? 0 : max(n, 0)));
    const float f = emcv_gamma_luminance(scattered);

    // Update: cv's robust push of (f, G) and its noise test, spvg's push of f, and the residual at the previous
    // alpha.
    const float alpha = emcv_history_predicted_alpha(cov);
    const float residual_value = emcv_cv_residual(f, alpha, g);
    // cv's noise test over a pool of this pixel alone (the renderer pools over the pixel's 8x8 tile).
    uvec3 noise_pool = uvec3(0u);
    // A pixel alone is a block of one (EMCV_HISTORY_BLOCK = 1): its batch is its own n.
    const float batch = emcv_history_block_batch(uint(max(n, 1)), 1u);
    emcv_history_noise_add(noise_pool, emcv_history_noise_term(cov, f, g, EMCV_HISTORY_ETA_EMCM, batch),
                           emcv_history_noise_relative(batch));
    emcv_history_push_cv(cov, f, g, EMCV_HISTORY_ETA_EMCM, float(max(n, 1)));
    emcv_history_rescale_cv(cov, emcv_history_noise_ratio(noise_pool));
    emcv_moving_stats_push_batch(stats, f, EMCV_HISTORY_ETA_MOVING, float(max(n, 1)));
    EmcvMovingStats res = residual.state[index];
    emcv_moving_stats_push(res, residual_value, EMCV_HISTORY_ETA_MOVING);
    // cv-notex's push (its residual f - G at alpha = 1, with cv's change test) into a copy of that state.
    EmcvMovingStats notex = res;
    emcv_history_push_notex(notex, f, g, EMCV_HISTORY_ETA_MOVING, float(max(n, 1)));
    EmcvEmcm2 plain = covariance.state[index];
    emcv_emcm2_push(plain, vec2(f, g), EMCV_HISTORY_ETA_EMCM);
    covariance.state[index] = plain;
    residual.state[index] = res;

    // The budget's histogram of sigma (budget.h): bin, fraction, and a bin's share at the current lambda.
    const float sigma = sqrt(max(emcv_cv_optimal_residual_variance_emcm2(cov), 0.0f));
    const uint bin = emcv_budget_bin(sigma);
    atomicAdd(budget.block.bin_count[bin], 1u);
    atomicAdd(budget.block.bin_fraction[bin], emcv_budget_fraction(sigma));
    const float bin_sum = emcv_budget_bin_sum(bin, 1u, emcv_budget_fraction(sigma));
    const float share = emcv_budget_bin_samples(budget.block.lambda, bin_sum, 1u, float(EMCV_HISTORY_N_MIN),
                                                float(EMCV_HISTORY_N_MAX));
    const uint lambda_span = emcv_budget_lambda_high_bits() - emcv_budget_lambda_low_bits();
    const float hashed = emcv_uint_to_unit_float(emcv_pcg(index)) + emcv_hammersley(index, width).y + notex.mean +
                         emcv_sss_sample_uv_sobol(index, rotation).x +
                         emcv_burley_sample_exact(emcv_r2(index).x, 1.0f) + emcv_burley_cdf(1.0f, 1.0f) +
                         emcv_burley_profile(1.0f, 1.0f) + emcv_bits_float(emcv_float_bits(share)) +
                         emcv_cv_residual_variance(cov.cov.x, cov.cov.y, cov.cov.z, alpha) +
                         emcv_cv_coefficient_floor(cov.cov.y, cov.cov.z, emcv_float_min_normal()) +
                         float(emcv_sample_count(sigma2, EMCV_HISTORY_TARGET, 1, 64)) + float(lambda_span) *
                         emcv_history_no_samples() * emcv_history_no_variance() * emcv_history_change_z2() *
                         emcv_history_unbias(0.2f) * emcv_history_variance_unit();

    // Encode the histories, write the count and the display value.
    imageStore(history_cov, texel, emcv_history_encode_emcm2_cov(cov));
    imageStore(history_means, texel, vec4(emcv_history_encode_emcm2_means(cov), 0.0f, 0.0f));
    imageStore(history_stats, texel, emcv_history_encode_stats(stats));
    imageStore(sample_count, texel, uvec4(uint(max(n, 0))));
    const vec3 linear = scattered * albedo + vec3(emcv_is_nan(hashed) ? 1.0f : 0.0f);
    const vec3 shown = emcv_rgb_to_ycocg(emcv_display_encode(linear, int(frame_index & 1u)) * emcv_srgb_encode(1.0f));

    // The temporal resolve (resolve.h): the last displayed value as the history, clipped to a box around the
    // pixel itself (a one-pixel neighbourhood), blended; reset where its depth is not this surface's.
    const vec4 previous = imageLoad(display, texel);
    const vec4 taps = emcv_resolve_catmull_rom(fract(float(frame_index) * 0.25f));  // a resampled history's weights
    vec3 history = emcv_rgb_to_ycocg(previous.rgb) * (taps.x + taps.y + taps.z + taps.w);
    // The guide (resolve.h): the unscattered light times the albedo, its change since the history from the
    // history's own value (here the history stands in for last frame's guide), at the slope of a one-pixel fit
    // (no spread: 0, the history as it is).
    const vec3 guide = emcv_rgb_to_ycocg(emcv_display_encode(albedo * scattered, int(frame_index & 1u)));
    const vec3 guide_history = history;
    history = emcv_resolve_guided_history(history, emcv_resolve_guide_slope(vec3(0.0f), vec3(0.0f), 1.0f), guide, history);
    // The weight the guide's change asks of the blend (no spread in one value: 0).
    const float guide_weight = emcv_resolve_guide_weight(guide - guide_history, vec3(0.0f), 1.0f);
    vec3 lo, hi;
    emcv_resolve_clip_box(shown, shown * shown, 1.0f, shown, lo, hi);
    // The noise box (resolve.h): this pixel's own variance as its neighbourhood's (one pixel here), its deviation
    // through the display encoding both ways, as the renderer does.
    const float noise_variance = emcv_resolve_pooled_noise(noise, max(noise, 0.0f), 1.0f, uint(max(n, 0)));
    const vec3 noise_extent = emcv_resolve_noise_extent(linear, emcv_ycocg_to_rgb(shown),
                                                        vec3(float(EMCV_RESOLVE_NOISE_SIGMA) * sqrt(max(noise_variance, 0.0f))),
                                                        int(frame_index & 1u));
    if (noise_variance >= 0.0f) emcv_resolve_narrow_to_noise(shown, noise_extent, lo, hi);
    // The clip's target: the current value filtered over a neighbourhood (here the pixel alone, weight 1/4 of the
    // 3x3 filter's 4/4 at the centre, renormalised) with the detail the history's neighbourhood shows put back
    // (one value each here: no spread, the filtered value), clipped into the box towards the current value.
    const vec3 filtered = shown * (emcv_resolve_filter_weight(0, 0) * 4.0f);
    const vec3 detailed = emcv_resolve_target(shown, filtered, emcv_resolve_variance(shown, shown * shown, 1.0f),
                                              emcv_resolve_variance(history, history * history, 1.0f));
    const vec3 target = emcv_resolve_clip(detailed, shown, lo, hi);
    if (emcv_resolve_same_surface(previous.a, frame.camera.w))
        history = emcv_resolve_blend(emcv_resolve_clip(history, target, lo, hi), shown,
                                     noise_variance >= 0.0f ? max(max(emcv_resolve_current_weight(history, shown, noise_extent),
                                                                      emcv_resolve_shift_weight(shown - history, noise_extent, 1.0f)),
                                                                  guide_weight)
                                                            : EMCV_RESOLVE_BLEND);
    else
        history = shown;
    // The display's inverse (tonemap.h), through which the renderer's resolve adds the specular light back
    // (none here: the value round-trips).
    const vec3 relit = emcv_display_encode(emcv_display_decode(emcv_ycocg_to_rgb(history), 0), 0);
    imageStore(display, texel, vec4(relit, 1.0f));
}
