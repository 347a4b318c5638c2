// SPDX-License-Identifier: MIT
// Camera and light matrices of a frame, scene bounds and the view-frustum test (CPU side of the pass list).
#pragma once

#include <glm/glm.hpp>

#include "scene/scene.hpp"

namespace emcv::demo {

struct view_matrices {
    glm::mat4 view{1.0f};
    glm::mat4 proj{1.0f};
    glm::mat4 view_proj{1.0f};
    glm::vec3 position{0.0f};
    glm::vec3 target{0.0f};
    /// The sub-pixel offset `proj` moves the image by, in pixels (taa_jitter; 0 without jitter).
    glm::vec2 jitter{0.0f};
    bool jittered = false;  ///< made by jittered()
};

/// Whether two cameras are the same bit for bit (view and projection): the rasteriser then writes the same
/// G-buffer, objects not moving in the scene model.
bool same_camera(const view_matrices& a, const view_matrices& b);

/// The temporal resolve's camera jitter at `frame`, in pixels, each component in (-0.5, 0.5): the Halton (2, 3)
/// points 1-8 (`frame mod 8` + 1) less 0.5, as TAA implementations jitter, so that over 8 frames a still pixel's
/// samples cover its area and the resolve's history accumulates its anti-aliased value.
glm::vec2 taa_jitter(int frame);

/// `v` with its projection offset so that the image moves by `jitter` pixels (a translation in clip space: the
/// depth and the scale are unchanged), view_proj updated.
view_matrices jittered(view_matrices v, glm::vec2 jitter, int width, int height);

/// The camera at `frame` for a width x height viewport (OpenGL clip space, right-handed, -z forward).
view_matrices camera_matrices(const camera& c, int frame, int width, int height);

struct bounding_sphere {
    glm::vec3 centre{0.0f};
    float radius = 0.0f;
};

/// A sphere around the object's transformed mesh (its AABB's, scaled by the largest axis of the model matrix).
bounding_sphere object_bounds(const scene& s, const object& o);

/// A sphere around every object of the scene (radius >= a small epsilon, for the shadow fits).
bounding_sphere scene_bounds(const scene& s);

/// True when the sphere intersects the frustum of view_proj (planes of Gribb & Hartmann, conservative).
bool sphere_in_frustum(const glm::mat4& view_proj, const bounding_sphere& b);

/// The view-projection of a light's shadow map: directional, orthographic around the scene bounds; spot,
/// perspective over its outer cone out to the far side of the scene bounds. Point lights have none.
glm::mat4 shadow_view_proj(const light& l, const bounding_sphere& scene_sphere);

/// Lights that get a shadow pass: casts_shadow and not a point light (point lights never cast here: a cube
/// map per point light is left out; pass_list documents it).
bool light_has_shadow_pass(const light& l);

/// Whether a light shines at `frame` (its intensity curve is above 0 there). A dark light records no shadow
/// pass that frame and the lighting pass skips it: nothing it would compute reaches the image.
bool light_shines(const light& l, int frame);

/// World size of one shadow-map texel near the scene (the normal offset of the shadow test).
float shadow_texel_world(const light& l, const bounding_sphere& scene_sphere, int resolution);

}  // namespace emcv::demo
