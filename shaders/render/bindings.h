// SPDX-License-Identifier: MIT
// shaders/render/bindings.h — binding slots of the renderer's passes, read by the host (demo/render, C++) and
// by the GLSL passes from this one file (the pattern of include/emcv/port/bindings.h). Buffer and texture
// numbers are unique across those types (Vulkan shares one binding space per set); images are numbered apart.
#ifndef EMCV_RENDER_BINDINGS_H
#define EMCV_RENDER_BINDINGS_H

#define EMCV_RENDER_TILE_SIZE 8  // SSS tiles and compute workgroups are 8x8 pixels
// SSS tile dispatches are 2-D, EMCV_RENDER_TILE_ROW workgroups per row: one row of n tiles would exceed GL's
// guaranteed 65535 workgroups per dimension from 2048x2048 pixels on. Only the shaders read it (the dispatch's
// arguments are written on the GPU, render/tiles.h): a copy of shaders/ that defines it first runs narrower rows
// (tests/render, "SSS tiles dispatched in many rows").
#ifndef EMCV_RENDER_TILE_ROW
#define EMCV_RENDER_TILE_ROW 1024
#endif

// Buffers
#define EMCV_RENDER_FRAME 0       // uniform block: camera, viewport, frame constants (frame.h)
#define EMCV_RENDER_LIGHTS 1      // storage: per-light radiance at this frame, shadow matrices
#define EMCV_RENDER_MATERIALS 2   // storage: albedo, mean free path, specular per material
#define EMCV_RENDER_OBJECTS 3     // storage: model and normal matrices, material per object
#define EMCV_RENDER_STATS 4       // storage: SSS pixel count, sum and max of samples (GPU reduction)
#define EMCV_RENDER_TILES 5       // storage: indirect dispatch arguments, then the SSS tile list
#define EMCV_RENDER_KERNELS 6     // storage: separable kernels, taps per material
#define EMCV_RENDER_PASS 7        // uniform block: per-pass constants (separable direction)

// Textures read by sampling (texelFetch or filtered)
#define EMCV_RENDER_TEX_ALBEDO_MAP 8   // gbuffer: the object's albedo texture (white 1x1 when none)
#define EMCV_RENDER_TEX_SHADOWS 9      // lighting: shadow maps, one array layer per casting light
#define EMCV_RENDER_TEX_DEPTH 10       // linear view depth (R32F, world units, 0 = background)
#define EMCV_RENDER_TEX_NORMAL 11      // world normal (RGBA16F)
#define EMCV_RENDER_TEX_ALBEDO 12      // surface albedo with its texture (RGBA16F, linear)
#define EMCV_RENDER_TEX_MATERIAL 13    // material index + 1 (R8UI, 0 = background)
#define EMCV_RENDER_TEX_DIFFUSE 14     // diffuse irradiance / pi, no albedo (RGBA16F)
#define EMCV_RENDER_TEX_SPECULAR 15    // specular radiance (RGBA16F)
#define EMCV_RENDER_TEX_SSS_IN 16      // separable: the horizontal pass's output; composite: scattered
#define EMCV_RENDER_TEX_MOTION 17      // motion in pixels, current - previous (RG16F)
#define EMCV_RENDER_TEX_RESOLVE_CURRENT 18  // resolve: the composite's linear HDR image
#define EMCV_RENDER_TEX_RESOLVE_HISTORY 19  // resolve: last frame's resolved display values and view depth
#define EMCV_RENDER_TEX_SSS_COUNT 20       // resolve: samples per pixel (R32UI) of this frame's burley pass
#define EMCV_RENDER_TEX_RESOLVE_GUIDE 21   // resolve: last frame's guide (the unscattered composite, display YCoCg)

// Images written by compute passes: image units are their own small space (0..7, EMCV_MAX_IMAGE_UNITS in
// emcv/port/bindings.h; NVIDIA has 8), so passes that never run together share units, and each pass binds its
// images right before its dispatch. The burley pass reads EMCV_ADAPTIVE_IMG_SAMPLES (2) beside SSS_OUT and
// COUNT, so the adaptive images (2-4) are kept off 0 and 1.
#define EMCV_RENDER_IMG_DIFFUSE 0      // lighting
#define EMCV_RENDER_IMG_SPECULAR 1     // lighting
#define EMCV_RENDER_IMG_SSS_OUT 0      // sss-burley, sss-separable-*
#define EMCV_RENDER_IMG_COUNT 1        // samples per pixel (R32UI), bound before the adaptive samples pass
#define EMCV_RENDER_IMG_LINEAR 0       // composite: linear HDR
#define EMCV_RENDER_IMG_DISPLAY 1      // composite: tonemapped, sRGB-encoded
#define EMCV_RENDER_IMG_RESOLVE_HISTORY 0  // resolve: this frame's resolved display values and view depth
#define EMCV_RENDER_IMG_RESOLVED 1     // resolve: the resolved display image (RGBA8)
#define EMCV_RENDER_IMG_RESOLVE_GUIDE 2  // resolve: this frame's guide

// Material kinds in materials[i].albedo.w
#define EMCV_RENDER_MATERIAL_DIFFUSE 0
#define EMCV_RENDER_MATERIAL_SSS 1

// Light kinds in lights[i].radiance.w
#define EMCV_RENDER_LIGHT_DIRECTIONAL 0
#define EMCV_RENDER_LIGHT_POINT 1
#define EMCV_RENDER_LIGHT_SPOT 2

// frame.counters.w bits
#define EMCV_RENDER_FLAG_SSS_RAN 1u         // composite reads the scattered diffuse at SSS pixels
#define EMCV_RENDER_FLAG_APPROXIMATE_CDF 2u // Burley radii from SPVG's approximation
#define EMCV_RENDER_FLAG_SSS_TILES 4u       // SSS passes follow: the lighting pass lists the SSS tiles
#define EMCV_RENDER_FLAG_JITTER 8u          // the camera jitters (--jitter): the resolve's history test is the neighbourhood's
#define EMCV_RENDER_FLAG_SSS_NOISE 16u      // frame_planner::resolves_sss_noise: the burley pass stores emcv_sss_noise in its alpha

#define EMCV_RENDER_MAX_SEPARABLE_TAPS 25

// tests/render: shaders/tests/burley_radii.comp.glsl
#define EMCV_RENDER_TEST_PARAMS 0   // uniform block
#define EMCV_RENDER_TEST_OUTPUT 1   // storage: one radius per invocation

#endif  // #ifndef EMCV_RENDER_BINDINGS_H
