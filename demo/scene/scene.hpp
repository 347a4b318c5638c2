// SPDX-License-Identifier: MIT
// emcv::demo scene model: what a scene file describes, after parsing and mesh loading, in world units.
// Data flows one way (docs/architecture.md): scene file -> scene (this header) -> pass list -> GPU passes -> images + metrics.
// The renderer reads a scene; it never parses files and never changes the scene.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace emcv::demo {

/// A scalar over frames (light intensity). Frames are 0-based.
struct curve {
    enum class kind {
        constant,  ///< `value` at every frame
        steps,     ///< `value` before the first step; from frame steps[i].first on, steps[i].second (switch off/on)
        flicker,   ///< `value`, except for `burst_length` frames from each of `bursts` at `peak` (gunshots)
        sinusoid   ///< value + amplitude * sin(2 pi frame / period_frames + phase) (club lighting), floored at 0
    };
    kind type = kind::constant;
    float value = 1.0f;
    std::vector<std::pair<int, float>> steps;  ///< steps: sorted by frame
    std::vector<int> bursts;                   ///< flicker: start frames, sorted
    int burst_length = 1;                      ///< flicker
    float peak = 0.0f;                         ///< flicker
    float amplitude = 0.0f;                    ///< sinusoid
    float period_frames = 1.0f;                ///< sinusoid, > 0
    float phase = 0.0f;                        ///< sinusoid, radians

    float at(int frame) const;
    /// True when at(f) is the same for every frame f >= 0 (a constant, or steps/flicker/sinusoid that never
    /// change the value). A light whose curve is constant needs no temporal machinery.
    bool is_constant() const;
};

/// Camera: a pinhole looking from `position` at `target`. `keys` (optional) move position and target over
/// frames, linearly between keyframes and held outside them.
struct camera {
    glm::vec3 position{0.0f, 0.0f, 5.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fov_y_degrees = 30.0f;
    float near_plane = 0.05f;
    float far_plane = 100.0f;
    struct key {
        int frame = 0;
        glm::vec3 position{0.0f};
        glm::vec3 target{0.0f};
    };
    std::vector<key> keys;  ///< sorted by frame; empty: a static camera

    /// Position and target at a frame (keys interpolated).
    std::pair<glm::vec3, glm::vec3> at(int frame) const;
    bool is_static() const;  ///< fewer than two keys, or all keys equal
};

/// Triangle mesh in object space. Normals are unit length; uv is (0, 0) where the source had none.
struct vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 uv;
};
struct mesh {
    std::string name;  ///< "sphere", "torus", ... or the file name
    std::vector<vertex> vertices;
    std::vector<std::uint32_t> indices;  ///< triangles
};

/// Linear RGBA texels, bottom row first (GL order), read from an 8-bit sRGB image and linearised.
struct texture {
    std::filesystem::path path;
    int width = 0;
    int height = 0;
    std::vector<float> rgba;
};

/// How a surface shades. Scattering applies to the diffuse part only; the specular lobe is added after it.
struct material {
    enum class kind { diffuse, sss };
    std::string name;
    kind type = kind::diffuse;
    glm::vec3 albedo{0.8f};       ///< linear surface albedo A per channel, in [0, 1]
    int albedo_texture = -1;      ///< index into scene::textures, multiplies `albedo`; -1: none
    glm::vec3 mean_free_path_mm{1.0f};  ///< sss: per-channel diffuse mean free path l (mm), > 0
    float specular = 0.0f;        ///< weight of the specular lobe (GGX), 0: none
    float roughness = 0.5f;       ///< GGX roughness in (0, 1]

    bool scatters() const { return type == kind::sss; }
};

/// One mesh placed in the world with one material.
struct object {
    std::string name;
    int mesh = 0;      ///< index into scene::meshes
    int material = 0;  ///< index into scene::materials
    glm::mat4 model{1.0f};  ///< object -> world (translate * rotate * scale)
};

struct light {
    enum class kind { directional, point, spot };
    std::string name;
    kind type = kind::directional;
    glm::vec3 color{1.0f};           ///< linear RGB, multiplied by the intensity curve
    curve intensity;                 ///< irradiance (directional) or intensity (point/spot, falls off as 1/d^2)
    glm::vec3 position{0.0f};        ///< point, spot
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  ///< directional, spot: unit vector the light travels along
    float inner_cone_degrees = 20.0f;  ///< spot: full intensity inside
    float outer_cone_degrees = 30.0f;  ///< spot: zero outside
    bool casts_shadow = false;       ///< a shadow map is rendered for this light (and only for this one)
};

struct scene {
    std::string name;                  ///< file stem ("light-off")
    std::filesystem::path source;      ///< the file it was read from
    std::string description;
    float mm_per_unit = 1.0f;          ///< world scale: millimetres per world unit (> 0)
    int frames = 1;                    ///< default sequence length (--frames overrides)
    glm::vec3 background{0.0f};        ///< linear RGB behind every object
    glm::vec3 ambient{0.0f};           ///< linear RGB irradiance added to every diffuse surface
    camera view;
    std::vector<mesh> meshes;
    std::vector<texture> textures;
    std::vector<material> materials;
    std::vector<object> objects;
    std::vector<light> lights;

    /// True when some object has a scattering material (visibility is the renderer's question).
    bool has_sss_material() const;
};

}  // namespace emcv::demo
