// SPDX-License-Identifier: MIT
// The renderer's GPU resources (programs, geometry, buffers, targets, shadow maps), made once for a scene, a
// method and a size, and the frame context the passes (passes/) record from. render() allocates nothing.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "gl/handles.hpp"
#include "gl/program.hpp"
#include "gpu_types.hpp"
#include "method.hpp"
#include "program_cache.hpp"
#include "render_options.hpp"
#include "scene/scene.hpp"
#include "view.hpp"

namespace emcv::demo {

namespace adaptive {
class history;  // demo/render/adaptive/history.hpp
}

/// Shadow maps are square, this many texels a side.
inline constexpr int shadow_resolution = 1024;

/// The programs the passes use, from one program_cache (which adaptive::history draws the adaptive passes' from
/// too). Only the programs of passes the scene and method can record are set (prepare_pass_programs); using
/// another throws.
struct pass_programs {
    explicit pass_programs(program_cache& programs) : cache(&programs) {}
    program_cache* cache;
    program_ref gbuffer{nullptr, "gbuffer"}, shadow{nullptr, "shadow"}, lighting{nullptr, "lighting"};
    program_ref separable{nullptr, "sss-separable"}, composite{nullptr, "composite"};
    program_ref resolve{nullptr, "resolve"};  ///< --resolve taa only
    /// The burley pass of burley-N, the reference and their variants, built with the row's shader_defines();
    /// an adaptive method's is its history's.
    program_ref burley{nullptr, "sss-burley"};
};

/// The shader options every pass is built with: include roots (render_options, else $EMCV_SHADER_DIR /
/// $EMCV_INCLUDE_DIR, else the source tree) and the tunables' defines.
struct shader_setup {
    gl::preprocess_options preprocess;
    std::filesystem::path shader_dir;
};
shader_setup make_shader_setup(const render_options& o);
/// Sets p's programs for what method m can record on scene s, from p's cache: the G-buffer, lighting and
/// composite passes always; the shadow pass where a light casts shadows; burley-N's and the reference's burley
/// pass, or the separable passes; the resolve under resolve taa. A method switch calls it again for the new
/// method (a program once built stays in the cache). A renderer compiles no program it never dispatches.
void prepare_pass_programs(pass_programs& p, const scene& s, const method& m, resolve_mode resolve);

struct draw_call {
    GLsizei index_count = 0;
    std::size_t index_offset_bytes = 0;
    GLint base_vertex = 0;
    GLuint object = 0;
    int albedo_map = -1;
};

struct gpu_resources {
    int width = 0;
    int height = 0;

    // Geometry: every mesh in one vertex and index buffer, one draw per object (sorted by albedo map).
    gl::buffer vertices, indices, object_ids;
    gl::vertex_array vao;
    std::vector<draw_call> draws;
    std::vector<gl::texture_2d> albedo_maps;
    gl::texture_2d white;
    bounding_sphere world_bounds;

    gl::buffer frame_ubo, lights_ssbo, materials_ssbo, objects_ssbo, stats_ssbo, tiles_ssbo, kernels_ssbo, pass_ubo;
    GLint pass_stride = 256;  ///< bytes between per-pass constant ranges in pass_ubo

    gl::texture_2d depth_buffer, gb_depth, gb_normal, gb_albedo, gb_material, gb_motion, lit_diffuse, lit_specular,
        sss_out, sss_temp, counts, linear_out, display_out;
    gl::framebuffer gbuffer_fbo;
    /// The previous frame's depth, normal and material (the adaptive methods' reprojection; empty otherwise):
    /// the G-buffer ping-pongs with them (swap_gbuffer), nothing is copied.
    gl::texture_2d prev_gb_depth, prev_gb_normal, prev_gb_material;
    /// The temporal resolve's (--resolve taa; empty otherwise): this frame's history written, the previous
    /// frame's read (RGBA32F: resolved display values in YCoCg and the view depth, 0 = no history; binary16
    /// would do on hardware that rounds, but llvmpipe's binary16 store truncates, and the history, stored 20 times
    /// over, walked a still pixel 2 steps off), and the resolved display image (RGBA8).
    gl::texture_2d resolve_history, resolve_history_previous, resolved_display;
    /// The resolve's guide (without jitter; empty under it, where the resolve does not follow a guide), this
    /// frame's written and the previous frame's read with the history (swapped with it): the unscattered
    /// composite in display YCoCg (RGBA16F; the shader rounds each value to binary16 itself before the store, so
    /// the store is exact under any rounding and a still guide reads back as it is computed).
    gl::texture_2d resolve_guide, resolve_guide_previous;
    gl::texture_2d shadow_maps;  ///< GL_TEXTURE_2D_ARRAY, one layer per light in shadow_lights
    std::vector<gl::framebuffer> shadow_fbos;
    std::vector<std::size_t> shadow_lights;  ///< light index per layer

    /// Range of pass_ubo for slot k: shadow layers first, then the separable passes' two directions.
    GLintptr pass_offset(std::size_t slot) const { return GLintptr{pass_stride} * static_cast<GLintptr>(slot); }
    std::size_t separable_slot(int direction) const { return shadow_lights.size() + static_cast<std::size_t>(direction); }
    /// Draws every object (gbuffer: binding each albedo map; shadow: geometry only).
    void draw_objects(bool with_albedo_maps) const;
};

/// Validates the scene against the renderer's limits and makes every resource of the frame. Throws
/// std::runtime_error naming the problem (a bad size, a texture without pixels, an incomplete framebuffer).
gpu_resources make_gpu_resources(const scene& s, const method& m, int width, int height);

/// Allocates the previous frame's G-buffer targets once (an adaptive method runs: its reprojection reads them),
/// with material 0 everywhere, so that the next frame keeps no history. Idempotent.
void make_previous_gbuffer(gpu_resources& r);
/// The frame just rendered becomes the previous one: its depth, normal and material targets trade places with
/// the previous frame's, and the G-buffer framebuffer renders into the others next (no copy).
void swap_gbuffer(gpu_resources& r);
/// Marks the previous frame's G-buffer unusable (material 0): the next frame keeps no history anywhere.
void forget_previous_gbuffer(gpu_resources& r);

/// Allocates the temporal resolve's targets (--resolve taa), its history empty; with `guide` (no jitter) its
/// guide textures too.
void make_resolve_targets(gpu_resources& r, bool guide);
/// The resolve history just written becomes the previous one (no copy).
void swap_resolve_history(gpu_resources& r);
/// Empties the previous resolve history (view depth 0 everywhere): the next resolve starts from the raw frame.
void forget_resolve_history(gpu_resources& r);

/// Materials and, for the separable method, their kernels (built on the CPU from each SSS material's profile).
void upload_materials(gpu_resources& r, const scene& s, const method& m);

/// How many tiles of EMCV_RENDER_TILE_SIZE pixels cover `pixels` along one side: the SSS tile list's length and
/// the full-screen dispatch's workgroups.
GLuint tiles_covering(int pixels);

/// What a pass records from: the resources, this frame's scene and method, and the adaptive history.
struct frame_context {
    gpu_resources& res;
    const pass_programs& programs;
    const scene& s;
    const method& m;
    adaptive::history* history;  ///< the adaptive methods' (nullptr for the others)
    int frame;
    GLuint groups_x, groups_y;   ///< full-screen compute dispatch, EMCV_RENDER_TILE_SIZE pixels a side
    bool sss_passes;             ///< SSS passes run this frame: the lighting pass lists their tiles
};

}  // namespace emcv::demo
