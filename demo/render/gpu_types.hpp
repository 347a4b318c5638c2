// SPDX-License-Identifier: MIT
// Host mirrors of the GLSL blocks in shaders/render/frame.h and objects.h (std140 / std430). Members are vec4,
// uvec4, ivec4 and mat4 only, so both layouts equal the C++ layout; the static_asserts keep them in step.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace emcv::demo::gpu {

struct frame_block {
    glm::mat4 view;
    glm::mat4 proj;
    glm::mat4 view_proj;
    glm::mat4 prev_view_proj;
    glm::mat4 inv_view;
    glm::vec4 camera_position;  // w: mm per unit
    glm::vec4 viewport;         // w, h, 1/w, 1/h
    glm::vec4 projection;       // P00, P11, near, far
    glm::vec4 background;       // w: exposure
    glm::vec4 ambient;          // w: tonemap
    glm::uvec4 counters;        // frame, seed, light count, flags
    glm::ivec4 sss;             // fixed samples, adaptive (1: N per pixel), material count, unused
};
static_assert(sizeof(frame_block) == 5 * 64 + 7 * 16, "frame_block must match shaders/render/frame.h");

struct light_block {
    glm::vec4 radiance;   // w: kind
    glm::vec4 position;   // w: shadow layer or -1
    glm::vec4 direction;  // w: cos outer
    glm::vec4 cone;       // x: cos inner, y: normal offset (world), z: depth bias
    glm::mat4 shadow_view_proj;
};
static_assert(sizeof(light_block) == 128, "light_block must match shaders/render/frame.h");

struct material_block {
    glm::vec4 albedo;          // w: kind
    glm::vec4 mean_free_path;  // mm
    glm::vec4 specular;        // weight, roughness
    glm::vec4 separable;       // half-width mm, taps
};
static_assert(sizeof(material_block) == 64, "material_block must match shaders/render/frame.h");

struct object_block {
    glm::mat4 model;
    glm::mat4 normal_matrix;
    glm::ivec4 material;
};
static_assert(sizeof(object_block) == 144, "object_block must match shaders/render/objects.h");

struct pass_block {
    glm::ivec4 ints;
    glm::vec4 floats;
};

struct stats_block {
    std::uint32_t sss_pixels;
    std::uint32_t sample_sum;
    std::uint32_t sample_max;
    std::uint32_t unused;
};

}  // namespace emcv::demo::gpu
