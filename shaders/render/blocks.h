// SPDX-License-Identifier: MIT
// shaders/render/blocks.h — the renderer's GPU blocks, written once in the dialect C++ and GLSL share
// (include/emcv/port/port.h). The GLSL passes declare their uniform and storage blocks with these structs
// (frame.h, objects.h, tiles.h); the host (demo/render, through gpu_types.hpp) fills the same structs.
// Members are vec4, uvec4, ivec4, mat4 and uint only, so std140, std430 and C++ (GLM) lay them out alike:
// gpu_types.hpp asserts the sizes.
#ifndef EMCV_RENDER_BLOCKS_H
#define EMCV_RENDER_BLOCKS_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace emcv { namespace demo { namespace gpu {
using namespace glm;
typedef std::uint32_t uint;
#endif

/// The frame's constants (uniform block EMCV_RENDER_FRAME).
struct EmcvFrameBlock {
    mat4 view;
    mat4 proj;
    mat4 view_proj;
    mat4 prev_view_proj;   // the previous frame's (motion vectors)
    mat4 inv_view;
    vec4 camera_position;  // xyz world, w: mm per world unit
    vec4 viewport;         // width, height, 1 / width, 1 / height
    vec4 projection;       // P00, P11, near, far
    vec4 background;       // linear rgb, w: exposure
    vec4 ambient;          // linear rgb irradiance, w: tonemap (0 ACES fitted, 1 Reinhard)
    uvec4 counters;        // frame, seed, light count, flags (EMCV_RENDER_FLAG_*)
    ivec4 sss;             // fixed samples per SSS pixel (0 for the adaptive methods: their burley program takes N per pixel), unused, material count, unused
    vec4 jitter;           // xy: this frame's sub-pixel camera offset in pixels (0 without --jitter), zw: the previous frame's
};

/// One light at this frame (storage buffer EMCV_RENDER_LIGHTS).
struct EmcvLight {
    vec4 radiance;    // rgb: colour * intensity(frame), w: kind (EMCV_RENDER_LIGHT_*)
    vec4 position;    // xyz world, w: shadow layer (-1: none)
    vec4 direction;   // xyz: unit direction the light travels, w: cos(outer cone)
    vec4 cone;        // x: cos(inner cone), y: normal offset (world), z: depth bias
    mat4 shadow_view_proj;
};

/// One material (storage buffer EMCV_RENDER_MATERIALS).
struct EmcvMaterial {
    vec4 albedo;           // linear rgb, w: kind (EMCV_RENDER_MATERIAL_*)
    vec4 mean_free_path;   // rgb mm (sss), w: unused
    vec4 specular;         // x: weight, y: roughness
    vec4 separable;        // x: kernel half-width in mm, y: taps
};

/// One object (storage buffer EMCV_RENDER_OBJECTS).
struct EmcvObject {
    mat4 model;          // object -> world
    mat4 normal_matrix;  // inverse transpose of model
    ivec4 material;      // x: material index
};

/// Per-pass constants (uniform block EMCV_RENDER_PASS, one range per pass): shadow passes x = light index;
/// separable passes xy = the direction.
struct EmcvPassBlock {
    ivec4 ints;
    vec4 floats;
};

/// The GPU's reduction over the SSS pixels (storage buffer EMCV_RENDER_STATS), read back once per frame.
struct EmcvStatsBlock {
    uint sss_pixels;
    uint sample_sum;
    uint sample_max;
    uint unused;
};

#ifdef __cplusplus
} } }  // namespace emcv::demo::gpu
#endif

#endif  // #ifndef EMCV_RENDER_BLOCKS_H
