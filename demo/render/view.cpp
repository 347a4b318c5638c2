// SPDX-License-Identifier: MIT
#include "view.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

namespace emcv::demo {

view_matrices camera_matrices(const camera& c, int frame, int width, int height) {
    view_matrices v;
    const auto [position, target] = c.at(frame);
    v.position = position;
    v.target = target;
    v.view = glm::lookAt(position, target, c.up);
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    v.proj = glm::perspective(glm::radians(c.fov_y_degrees), aspect, c.near_plane, c.far_plane);
    v.view_proj = v.proj * v.view;
    return v;
}

namespace {
/// The radical inverse of i in `base` (the Halton sequence's point i).
float radical_inverse(int i, int base) {
    float result = 0.0f, scale = 1.0f / float(base);
    for (; i > 0; i /= base, scale /= float(base)) result += float(i % base) * scale;
    return result;
}
}  // namespace

glm::vec2 taa_jitter(int frame) {
    const int index = (frame % 8 + 8) % 8 + 1;
    return {radical_inverse(index, 2) - 0.5f, radical_inverse(index, 3) - 0.5f};
}

view_matrices jittered(view_matrices v, glm::vec2 jitter, int width, int height) {
    // clip.x gains -2 j / width * z_view, and clip.w = -z_view: ndc.x moves by +2 j / width, j pixels.
    v.proj[2][0] -= 2.0f * jitter.x / float(width);
    v.proj[2][1] -= 2.0f * jitter.y / float(height);
    v.view_proj = v.proj * v.view;
    v.jitter = jitter;
    v.jittered = true;
    return v;
}

bounding_sphere object_bounds(const scene& s, const object& o) {
    const mesh& m = s.meshes.at(static_cast<std::size_t>(o.mesh));
    if (m.vertices.empty()) return {glm::vec3(o.model[3]), 0.0f};
    glm::vec3 lo = m.vertices.front().position;
    glm::vec3 hi = lo;
    for (const vertex& v : m.vertices) {
        lo = glm::min(lo, v.position);
        hi = glm::max(hi, v.position);
    }
    const glm::vec3 centre = 0.5f * (lo + hi);
    const float radius = 0.5f * glm::length(hi - lo);
    const float scale = std::max({glm::length(glm::vec3(o.model[0])), glm::length(glm::vec3(o.model[1])),
                                  glm::length(glm::vec3(o.model[2]))});
    return {glm::vec3(o.model * glm::vec4(centre, 1.0f)), radius * scale};
}

bounding_sphere scene_bounds(const scene& s) {
    if (s.objects.empty()) return {glm::vec3(0.0f), 1.0f};
    glm::vec3 lo(std::numeric_limits<float>::max());
    glm::vec3 hi(-std::numeric_limits<float>::max());
    for (const object& o : s.objects) {
        const bounding_sphere b = object_bounds(s, o);
        lo = glm::min(lo, b.centre - b.radius);
        hi = glm::max(hi, b.centre + b.radius);
    }
    return {0.5f * (lo + hi), std::max(0.5f * glm::length(hi - lo), 1e-3f)};
}

bool sphere_in_frustum(const glm::mat4& m, const bounding_sphere& b) {
    // Rows of the matrix (glm is column-major: m[col][row]).
    const glm::vec4 row0(m[0][0], m[1][0], m[2][0], m[3][0]);
    const glm::vec4 row1(m[0][1], m[1][1], m[2][1], m[3][1]);
    const glm::vec4 row2(m[0][2], m[1][2], m[2][2], m[3][2]);
    const glm::vec4 row3(m[0][3], m[1][3], m[2][3], m[3][3]);
    const glm::vec4 planes[6] = {row3 + row0, row3 - row0, row3 + row1, row3 - row1, row3 + row2, row3 - row2};
    for (const glm::vec4& p : planes) {
        const float norm = glm::length(glm::vec3(p));
        if (norm == 0.0f) continue;
        if ((glm::dot(glm::vec3(p), b.centre) + p.w) / norm < -b.radius) return false;
    }
    return true;
}

namespace {

/// An up vector not parallel to `direction`.
glm::vec3 up_for(const glm::vec3& direction) {
    return std::abs(direction.y) > 0.99f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
}

}  // namespace

glm::mat4 shadow_view_proj(const light& l, const bounding_sphere& b) {
    const glm::vec3 direction = glm::normalize(l.direction);
    if (l.type == light::kind::directional) {
        const glm::vec3 eye = b.centre - direction * (2.0f * b.radius);
        const glm::mat4 view = glm::lookAt(eye, b.centre, up_for(direction));
        return glm::ortho(-b.radius, b.radius, -b.radius, b.radius, b.radius, 3.0f * b.radius) * view;
    }
    const glm::mat4 view = glm::lookAt(l.position, l.position + direction, up_for(direction));
    const float far_plane = glm::length(b.centre - l.position) + b.radius;
    const float near_plane = std::max(far_plane * 1e-3f, 1e-3f);
    const float fov = glm::radians(std::min(2.0f * l.outer_cone_degrees + 2.0f, 170.0f));
    return glm::perspective(fov, 1.0f, near_plane, far_plane) * view;
}

float shadow_texel_world(const light& l, const bounding_sphere& b, int resolution) {
    if (l.type == light::kind::directional) return 2.0f * b.radius / static_cast<float>(resolution);
    const float distance = glm::length(b.centre - l.position);
    const float half_angle = glm::radians(std::min(l.outer_cone_degrees + 1.0f, 85.0f));
    return 2.0f * distance * std::tan(half_angle) / static_cast<float>(resolution);
}

bool same_camera(const view_matrices& a, const view_matrices& b) {
    return std::memcmp(&a.view, &b.view, sizeof a.view) == 0 && std::memcmp(&a.proj, &b.proj, sizeof a.proj) == 0;
}

}  // namespace emcv::demo
