// SPDX-License-Identifier: MIT
// The SSS renderer (renderer.hpp): GPU resources made once in the constructor, then per frame the pass list
// of the scene recorded with DSA calls, a debug group and a GPU timer per pass.
#include "renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include <glm/gtc/matrix_inverse.hpp>

#include <emcv/port/sss.h>

#include "gl/debug.hpp"
#include "gl/handles.hpp"
#include "gl/program.hpp"
#include "gl/timer.hpp"
#include "adaptive/history.hpp"
#include "gpu_types.hpp"
#include "render/bindings.h"
#include "targets.hpp"
#include "emcv/port/bindings.h"

// Image units (render/bindings.h): below the guaranteed minimum, and distinct within each pass.
static_assert(EMCV_RENDER_IMG_DIFFUSE < EMCV_MAX_IMAGE_UNITS && EMCV_RENDER_IMG_SPECULAR < EMCV_MAX_IMAGE_UNITS &&
              EMCV_RENDER_IMG_SSS_OUT < EMCV_MAX_IMAGE_UNITS && EMCV_RENDER_IMG_COUNT < EMCV_MAX_IMAGE_UNITS &&
              EMCV_RENDER_IMG_LINEAR < EMCV_MAX_IMAGE_UNITS && EMCV_RENDER_IMG_DISPLAY < EMCV_MAX_IMAGE_UNITS);
static_assert(EMCV_RENDER_IMG_DIFFUSE != EMCV_RENDER_IMG_SPECULAR && EMCV_RENDER_IMG_SSS_OUT != EMCV_RENDER_IMG_COUNT &&
              EMCV_RENDER_IMG_LINEAR != EMCV_RENDER_IMG_DISPLAY);
#include "separable_kernel.hpp"
#include "view.hpp"

namespace emcv::demo {

namespace fs = std::filesystem;

namespace {

constexpr int shadow_resolution = 1024;
constexpr int max_size = 8192;

fs::path resolve_dir(const fs::path& option, const char* environment, const char* compiled) {
    if (!option.empty()) return option;
    if (const char* value = std::getenv(environment); value != nullptr && *value != '\0') return value;
    return compiled;
}

GLuint div_up(int n, int d) { return static_cast<GLuint>((n + d - 1) / d); }

/// A mipmapped RGBA16F texture from linear RGBA floats (scene textures), or 1x1 white.
gl::texture_2d make_albedo_map(int width, int height, const float* rgba) {
    gl::texture_2d t = gl::texture_2d::create();
    int levels = 1;
    while ((std::max(width, height) >> levels) > 0) ++levels;
    glTextureStorage2D(t.id(), levels, GL_RGBA16F, width, height);
    glTextureSubImage2D(t.id(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, rgba);
    glGenerateTextureMipmap(t.id());
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GL_REPEAT);
    return t;
}

template <class T>
gl::buffer make_buffer(const T* data, std::size_t count, GLbitfield flags) {
    gl::buffer b = gl::buffer::create();
    glNamedBufferStorage(b.id(), static_cast<GLsizeiptr>(std::max<std::size_t>(count, 1) * sizeof(T)),
                         count > 0 ? data : nullptr, flags);
    return b;
}

gl::buffer make_dynamic_buffer(std::size_t bytes) {
    gl::buffer b = gl::buffer::create();
    glNamedBufferStorage(b.id(), static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 16)), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    return b;
}

void image_barrier_for_reads() {
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

}  // namespace

struct renderer::impl {
    // One timed pass: its name (as in pass_list), timer ring and newest measurement.
    struct timed_pass {
        std::string name;
        gl::gpu_timer timer;
        double last_ms = 0.0;
        bool recorded = false;
        std::chrono::steady_clock::time_point started{};
    };
    struct draw_call {
        GLsizei index_count = 0;
        std::size_t index_offset_bytes = 0;
        GLint base_vertex = 0;
        GLuint object = 0;
        int albedo_map = -1;
    };

    scene s;
    method m;
    render_options o;
    int width;
    int height;

    gl::program gbuffer_program, shadow_program, lighting_program, tiles_program, dispatch_program, burley_program,
        separable_program, composite_program;
    gl::preprocess_options shader_options;  // kept for the adaptive passes, built on a method switch
    fs::path shader_root;
    std::optional<adaptive::history> adaptive_state;  // spvg, cv, cv-notex only

    gl::buffer vertices, indices, object_ids;
    gl::vertex_array vao;
    std::vector<draw_call> draws;
    std::vector<gl::texture_2d> albedo_maps;
    gl::texture_2d white;
    std::vector<bounding_sphere> sss_object_bounds;

    gl::buffer frame_ubo, lights_ssbo, materials_ssbo, objects_ssbo, stats_ssbo, tiles_ssbo, kernels_ssbo, pass_ubo;
    GLint pass_stride = 256;

    gl::texture_2d depth_buffer, gb_depth, gb_normal, gb_albedo, gb_material, gb_motion, lit_diffuse, lit_specular,
        sss_out, sss_temp, counts, linear_out, display_out;
    gl::framebuffer gbuffer_fbo;
    gl::texture_2d shadow_maps;  // GL_TEXTURE_2D_ARRAY, one layer per shadow pass
    std::vector<gl::framebuffer> shadow_fbos;
    std::vector<std::size_t> shadow_lights;  // light index per layer

    // Pass slots: gbuffer, one per shadow layer, lighting, sss-tiles, sss-burley, sss-separable-h, -v, composite.
    std::vector<timed_pass> passes;
    std::size_t slot_lighting = 0, slot_tiles = 0, slot_burley = 0, slot_sep_h = 0, slot_sep_v = 0, slot_composite = 0;
    std::size_t slot_adaptive_samples = 0, slot_adaptive_update = 0;

    gpu::frame_block frame_data{};
    std::vector<gpu::light_block> light_data;
    std::vector<gpu::material_block> material_data;
    std::vector<float> light_scale;
    bounding_sphere world_bounds;
    glm::mat4 prev_view_proj{1.0f};
    bool has_previous = false;

    std::vector<float> signature, reference_signature;  // reference reuse: the frame's SSS inputs
    bool reference_valid = false;
    bool counts_dirty = true;
    frame_stats stats;
    double reference_mean_spp = 0.0;
    int reference_max_spp = 0;
    std::size_t reference_sss_pixels = 0;

    impl(const scene& sc, method me, render_options op);
    void build_programs();
    void make_adaptive_state();
    void upload_geometry();
    void make_targets();
    void upload_materials();
    void begin_pass(std::size_t slot);
    void end_pass(std::size_t slot);
    void draw_objects(bool with_albedo_maps);
    bool sss_visible(const glm::mat4& view_proj) const;
    void update_frame(int frame, const view_matrices& v, bool sss_ran);
    const frame_stats& render(int frame);
};

renderer::impl::impl(const scene& sc, method me, render_options op)
    : s(sc), m(me), o(std::move(op)), width(o.width), height(o.height) {
    if (width < 1 || height < 1 || width > max_size || height > max_size) {
        throw std::runtime_error("renderer: size " + std::to_string(width) + "x" + std::to_string(height) +
                                 " out of range (1.." + std::to_string(max_size) + " per side)");
    }
    if (!(o.exposure > 0.0f) || !std::isfinite(o.exposure)) throw std::runtime_error("renderer: exposure must be > 0");
    for (const object& ob : s.objects) {
        if (ob.mesh < 0 || static_cast<std::size_t>(ob.mesh) >= s.meshes.size() || ob.material < 0 ||
            static_cast<std::size_t>(ob.material) >= s.materials.size()) {
            throw std::runtime_error("renderer: object '" + ob.name + "' names a missing mesh or material");
        }
    }
    if (s.materials.size() > 254) throw std::runtime_error("renderer: at most 254 materials (8-bit material ids)");
    build_programs();
    upload_geometry();
    make_targets();
    make_adaptive_state();
    light_scale.assign(s.lights.size(), 1.0f);
    upload_materials();
    signature.assign(6 + 3 * s.lights.size(), 0.0f);
    reference_signature = signature;

    glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &pass_stride);
    pass_stride = std::max<GLint>(pass_stride, static_cast<GLint>(sizeof(gpu::pass_block)));
    std::vector<std::uint8_t> pass_bytes(static_cast<std::size_t>(pass_stride) * (shadow_lights.size() + 2), 0);
    for (std::size_t k = 0; k < shadow_lights.size(); ++k) {
        gpu::pass_block b{glm::ivec4(static_cast<int>(shadow_lights[k]), 0, 0, 0), glm::vec4(0.0f)};
        std::memcpy(pass_bytes.data() + k * static_cast<std::size_t>(pass_stride), &b, sizeof b);
    }
    for (std::size_t k = 0; k < 2; ++k) {
        gpu::pass_block b{k == 0 ? glm::ivec4(1, 0, 0, 0) : glm::ivec4(0, 1, 0, 0), glm::vec4(0.0f)};
        std::memcpy(pass_bytes.data() + (shadow_lights.size() + k) * static_cast<std::size_t>(pass_stride), &b,
                    sizeof b);
    }
    pass_ubo = make_buffer(pass_bytes.data(), pass_bytes.size(), 0);

    frame_ubo = make_dynamic_buffer(sizeof(gpu::frame_block));
    light_data.resize(s.lights.size());
    lights_ssbo = make_dynamic_buffer(sizeof(gpu::light_block) * std::max<std::size_t>(s.lights.size(), 1));
    stats_ssbo = make_dynamic_buffer(sizeof(gpu::stats_block));
    const std::size_t tile_count = std::size_t{div_up(width, EMCV_RENDER_TILE_SIZE)} * div_up(height, EMCV_RENDER_TILE_SIZE);
    tiles_ssbo = make_dynamic_buffer(16 + 4 * tile_count);

    // Timer slots, in recording order; names reserved once so render() allocates nothing.
    passes.push_back({"gbuffer", gl::gpu_timer(), 0.0, false});
    for (std::size_t light : shadow_lights) passes.push_back({"shadow:" + s.lights[light].name, gl::gpu_timer(), 0.0, false});
    const auto add = [&](const char* name) {
        passes.push_back({name, gl::gpu_timer(), 0.0, false});
        return passes.size() - 1;
    };
    slot_lighting = add("lighting");
    slot_tiles = add("sss-tiles");
    slot_adaptive_samples = add("sss-adaptive-samples");
    slot_burley = add("sss-burley");
    slot_adaptive_update = add("sss-adaptive-update");
    slot_sep_h = add("sss-separable-h");
    slot_sep_v = add("sss-separable-v");
    slot_composite = add("composite");
    stats.passes.resize(passes.size());
    for (std::size_t i = 0; i < passes.size(); ++i) stats.passes[i].name.reserve(passes[i].name.size() + 1);
}

void renderer::impl::build_programs() {
    gl::preprocess_options pre;
    const fs::path shader_dir = resolve_dir(o.shader_dir, "EMCV_SHADER_DIR", EMCV_SHADER_DIR);
    const fs::path include_dir = resolve_dir(o.include_dir, "EMCV_INCLUDE_DIR", EMCV_INCLUDE_DIR);
    pre.include_dirs = {shader_dir, include_dir};
    const fs::path dir = shader_dir / "render";
    gbuffer_program = gl::program::graphics(dir / "gbuffer.vert.glsl", dir / "gbuffer.frag.glsl", pre);
    shadow_program = gl::program::graphics(dir / "shadow.vert.glsl", dir / "shadow.frag.glsl", pre);
    lighting_program = gl::program::compute(dir / "lighting.comp.glsl", pre);
    tiles_program = gl::program::compute(dir / "sss_tiles.comp.glsl", pre);
    dispatch_program = gl::program::compute(dir / "sss_dispatch.comp.glsl", pre);
    burley_program = gl::program::compute(dir / "sss_burley.comp.glsl", pre);
    separable_program = gl::program::compute(dir / "sss_separable.comp.glsl", pre);
    composite_program = gl::program::compute(dir / "composite.comp.glsl", pre);
    shader_options = pre;
    shader_root = shader_dir;
}

/// The adaptive methods' history and passes, allocated only for them (demo/render/adaptive).
void renderer::impl::make_adaptive_state() {
    adaptive_state.reset();
    if (m.type == method::kind::spvg) adaptive_state.emplace(adaptive::kind::spvg, width, height, shader_options, shader_root);
    if (m.type == method::kind::cv) adaptive_state.emplace(adaptive::kind::cv, width, height, shader_options, shader_root);
    if (m.type == method::kind::cv_notex)
        adaptive_state.emplace(adaptive::kind::cv_notex, width, height, shader_options, shader_root);
}

void renderer::impl::upload_geometry() {
    std::vector<vertex> all_vertices;
    std::vector<std::uint32_t> all_indices;
    struct range { std::size_t first_index, index_count, first_vertex; };
    std::vector<range> ranges;
    for (const mesh& me : s.meshes) {
        ranges.push_back({all_indices.size(), me.indices.size(), all_vertices.size()});
        all_vertices.insert(all_vertices.end(), me.vertices.begin(), me.vertices.end());
        all_indices.insert(all_indices.end(), me.indices.begin(), me.indices.end());
    }
    static_assert(sizeof(vertex) == 32, "vertex: position, normal, uv, tightly packed");
    vertices = make_buffer(all_vertices.data(), all_vertices.size(), 0);
    indices = make_buffer(all_indices.data(), all_indices.size(), 0);
    std::vector<std::uint32_t> ids(s.objects.size());
    for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<std::uint32_t>(i);
    object_ids = make_buffer(ids.data(), ids.size(), 0);

    vao = gl::vertex_array::create();
    glVertexArrayVertexBuffer(vao.id(), 0, vertices.id(), 0, sizeof(vertex));
    glVertexArrayVertexBuffer(vao.id(), 1, object_ids.id(), 0, sizeof(std::uint32_t));
    glVertexArrayBindingDivisor(vao.id(), 1, 1);
    glVertexArrayElementBuffer(vao.id(), indices.id());
    glVertexArrayAttribFormat(vao.id(), 0, 3, GL_FLOAT, GL_FALSE, offsetof(vertex, position));
    glVertexArrayAttribFormat(vao.id(), 1, 3, GL_FLOAT, GL_FALSE, offsetof(vertex, normal));
    glVertexArrayAttribFormat(vao.id(), 2, 2, GL_FLOAT, GL_FALSE, offsetof(vertex, uv));
    glVertexArrayAttribIFormat(vao.id(), 3, 1, GL_UNSIGNED_INT, 0);
    for (GLuint a = 0; a < 4; ++a) {
        glEnableVertexArrayAttrib(vao.id(), a);
        glVertexArrayAttribBinding(vao.id(), a, a == 3 ? 1u : 0u);
    }

    std::vector<gpu::object_block> object_data;
    for (std::size_t i = 0; i < s.objects.size(); ++i) {
        const object& ob = s.objects[i];
        object_data.push_back({ob.model, glm::inverseTranspose(ob.model), glm::ivec4(ob.material, 0, 0, 0)});
        const range& r = ranges[static_cast<std::size_t>(ob.mesh)];
        const material& mat = s.materials[static_cast<std::size_t>(ob.material)];
        draws.push_back({static_cast<GLsizei>(r.index_count), r.first_index * sizeof(std::uint32_t),
                         static_cast<GLint>(r.first_vertex), static_cast<GLuint>(i), mat.albedo_texture});
        if (mat.scatters()) sss_object_bounds.push_back(object_bounds(s, ob));
    }
    // Sorted by albedo map so the texture binding changes once per map (no needless state changes).
    std::stable_sort(draws.begin(), draws.end(),
                     [](const draw_call& a, const draw_call& b) { return a.albedo_map < b.albedo_map; });
    objects_ssbo = make_buffer(object_data.data(), object_data.size(), 0);
    world_bounds = scene_bounds(s);

    const float one[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    white = make_albedo_map(1, 1, one);
    for (const texture& t : s.textures) {
        if (t.width < 1 || t.height < 1 || t.rgba.size() != std::size_t(t.width) * std::size_t(t.height) * 4) {
            throw std::runtime_error("renderer: texture " + t.path.string() + " has no pixels");
        }
        albedo_maps.push_back(make_albedo_map(t.width, t.height, t.rgba.data()));
    }
}

void renderer::impl::make_targets() {
    depth_buffer = make_target(GL_DEPTH_COMPONENT32F, width, height);
    gb_depth = make_target(GL_R32F, width, height);
    gb_normal = make_target(GL_RGBA16F, width, height);
    gb_albedo = make_target(GL_RGBA16F, width, height);
    gb_material = make_target(GL_R8UI, width, height);
    gb_motion = make_target(GL_RG16F, width, height);
    lit_diffuse = make_target(GL_RGBA16F, width, height);
    lit_specular = make_target(GL_RGBA16F, width, height);
    sss_out = make_target(GL_RGBA16F, width, height);
    sss_temp = make_target(GL_RGBA16F, width, height);
    counts = make_target(GL_R32UI, width, height);
    linear_out = make_target(GL_RGBA16F, width, height);
    display_out = make_target(GL_RGBA8, width, height);

    gbuffer_fbo = gl::framebuffer::create();
    const GLuint targets[5] = {gb_depth.id(), gb_normal.id(), gb_albedo.id(), gb_material.id(), gb_motion.id()};
    GLenum draw_buffers[5];
    for (GLuint i = 0; i < 5; ++i) {
        glNamedFramebufferTexture(gbuffer_fbo.id(), GL_COLOR_ATTACHMENT0 + i, targets[i], 0);
        draw_buffers[i] = GL_COLOR_ATTACHMENT0 + i;
    }
    glNamedFramebufferDrawBuffers(gbuffer_fbo.id(), 5, draw_buffers);
    glNamedFramebufferTexture(gbuffer_fbo.id(), GL_DEPTH_ATTACHMENT, depth_buffer.id(), 0);
    if (glCheckNamedFramebufferStatus(gbuffer_fbo.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        throw std::runtime_error("renderer: the G-buffer framebuffer is incomplete on this GL implementation");
    }

    for (std::size_t i = 0; i < s.lights.size(); ++i) {
        if (light_has_shadow_pass(s.lights[i])) shadow_lights.push_back(i);
    }
    GLuint array_id = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &array_id);
    shadow_maps = gl::texture_2d(array_id);
    const int side = shadow_lights.empty() ? 1 : shadow_resolution;
    glTextureStorage3D(array_id, 1, GL_DEPTH_COMPONENT32F, side, side,
                       static_cast<GLsizei>(std::max<std::size_t>(shadow_lights.size(), 1)));
    glTextureParameteri(array_id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(array_id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(array_id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(array_id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(array_id, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(array_id, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    for (std::size_t k = 0; k < shadow_lights.size(); ++k) {
        gl::framebuffer fbo = gl::framebuffer::create();
        glNamedFramebufferTextureLayer(fbo.id(), GL_DEPTH_ATTACHMENT, array_id, 0, static_cast<GLint>(k));
        glNamedFramebufferDrawBuffer(fbo.id(), GL_NONE);
        if (glCheckNamedFramebufferStatus(fbo.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            throw std::runtime_error("renderer: a shadow-map framebuffer is incomplete on this GL implementation");
        }
        shadow_fbos.push_back(std::move(fbo));
    }
}

/// Materials and, for `separable`, their kernels (built on the CPU from each SSS material's profile).
void renderer::impl::upload_materials() {
    material_data.clear();
    std::vector<glm::vec4> kernel_taps(std::max<std::size_t>(s.materials.size(), 1) * EMCV_RENDER_MAX_SEPARABLE_TAPS,
                                       glm::vec4(0.0f));
    for (std::size_t i = 0; i < s.materials.size(); ++i) {
        const material& mat = s.materials[i];
        gpu::material_block b{};
        b.albedo = glm::vec4(mat.albedo, mat.scatters() ? float(EMCV_RENDER_MATERIAL_SSS) : float(EMCV_RENDER_MATERIAL_DIFFUSE));
        b.mean_free_path = glm::vec4(mat.mean_free_path_mm, 0.0f);
        b.specular = glm::vec4(mat.specular, mat.roughness, 0.0f, 0.0f);
        if (mat.scatters() && m.type == method::kind::separable) {
            const glm::vec3 d = emcv::port::emcv_sss_shape_distance(mat.mean_free_path_mm, mat.albedo);
            const separable_kernel k = make_separable_kernel(d, m.samples);
            b.separable = glm::vec4(k.half_width_mm, float(m.samples), 0.0f, 0.0f);
            std::copy(k.taps.begin(), k.taps.end(), kernel_taps.begin() + static_cast<std::ptrdiff_t>(i * EMCV_RENDER_MAX_SEPARABLE_TAPS));
        }
        material_data.push_back(b);
    }
    materials_ssbo = make_buffer(material_data.data(), material_data.size(), 0);
    kernels_ssbo = make_buffer(kernel_taps.data(), kernel_taps.size(), 0);
}

// timing::per_frame brackets each pass with glFinish and the steady clock: the pass's own execution time on
// any device. On llvmpipe it is the only correct one: there, GL_TIME_ELAPSED queries do not cover compute
// dispatches (measured: 0.00 ms for every compute pass) and the frame's first query reads ~1e6 ms.
// timing::asynchronous uses the GPU timer ring (demo/gl/timer.hpp) and never waits.
void renderer::impl::begin_pass(std::size_t slot) {
    glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, passes[slot].name.c_str());
    passes[slot].recorded = true;
    if (o.timing_mode == timing::per_frame) {
        glFinish();
        passes[slot].started = std::chrono::steady_clock::now();
    } else {
        passes[slot].timer.begin();
    }
}

void renderer::impl::end_pass(std::size_t slot) {
    if (o.timing_mode == timing::per_frame) {
        glFinish();
        passes[slot].last_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - passes[slot].started).count();
    } else {
        passes[slot].timer.end();
    }
    glPopDebugGroup();
}

void renderer::impl::draw_objects(bool with_albedo_maps) {
    int bound = -2;
    for (const draw_call& d : draws) {
        if (with_albedo_maps && d.albedo_map != bound) {
            const GLuint t = d.albedo_map >= 0 ? albedo_maps[static_cast<std::size_t>(d.albedo_map)].id() : white.id();
            glBindTextureUnit(EMCV_RENDER_TEX_ALBEDO_MAP, t);
            bound = d.albedo_map;
        }
        glDrawElementsInstancedBaseVertexBaseInstance(GL_TRIANGLES, d.index_count, GL_UNSIGNED_INT,
                                                      reinterpret_cast<const void*>(d.index_offset_bytes), 1,
                                                      d.base_vertex, d.object);
    }
}

bool renderer::impl::sss_visible(const glm::mat4& view_proj) const {
    return std::any_of(sss_object_bounds.begin(), sss_object_bounds.end(),
                       [&](const bounding_sphere& b) { return sphere_in_frustum(view_proj, b); });
}

void renderer::impl::update_frame(int frame, const view_matrices& v, bool sss_ran) {
    frame_data.view = v.view;
    frame_data.proj = v.proj;
    frame_data.view_proj = v.view_proj;
    frame_data.prev_view_proj = has_previous ? prev_view_proj : v.view_proj;
    frame_data.inv_view = glm::inverse(v.view);
    frame_data.camera_position = glm::vec4(v.position, s.mm_per_unit);
    frame_data.viewport = glm::vec4(float(width), float(height), 1.0f / float(width), 1.0f / float(height));
    frame_data.projection = glm::vec4(v.proj[0][0], v.proj[1][1], s.view.near_plane, s.view.far_plane);
    frame_data.background = glm::vec4(s.background, o.exposure);
    frame_data.ambient = glm::vec4(s.ambient, o.tonemap == tonemap_operator::aces ? 0.0f : 1.0f);
    std::uint32_t flags = 0;
    if (sss_ran) flags |= EMCV_RENDER_FLAG_SSS_RAN;
    if (o.approximate_inverse_cdf) flags |= EMCV_RENDER_FLAG_APPROXIMATE_CDF;
    frame_data.counters = glm::uvec4(static_cast<std::uint32_t>(frame), o.seed,
                                     static_cast<std::uint32_t>(s.lights.size()), flags);
    const bool burley_like = m.type == method::kind::burley || m.type == method::kind::reference;
    frame_data.sss = glm::ivec4(burley_like ? m.samples : 0, adaptive_state ? 1 : 0, static_cast<int>(s.materials.size()), 0);
    glNamedBufferSubData(frame_ubo.id(), 0, sizeof frame_data, &frame_data);

    for (std::size_t i = 0; i < s.lights.size(); ++i) {
        const light& l = s.lights[i];
        gpu::light_block& b = light_data[i];
        const float kind = l.type == light::kind::directional ? float(EMCV_RENDER_LIGHT_DIRECTIONAL)
                           : l.type == light::kind::point     ? float(EMCV_RENDER_LIGHT_POINT)
                                                              : float(EMCV_RENDER_LIGHT_SPOT);
        b.radiance = glm::vec4(l.color * l.intensity.at(frame) * light_scale[i], kind);
        const auto layer = std::find(shadow_lights.begin(), shadow_lights.end(), i);
        // A dark light's layer was not rendered this frame (pass list): never read it.
        const float shadow_layer = layer == shadow_lights.end() || !light_shines(l, frame)
                                       ? -1.0f
                                       : float(layer - shadow_lights.begin());
        b.position = glm::vec4(l.position, shadow_layer);
        b.direction = glm::vec4(glm::normalize(l.direction), std::cos(glm::radians(l.outer_cone_degrees)));
        const float texel = shadow_texel_world(l, world_bounds, shadow_resolution);
        b.cone = glm::vec4(std::cos(glm::radians(l.inner_cone_degrees)), 1.5f * texel, 5e-4f, 0.0f);
        b.shadow_view_proj = shadow_layer >= 0.0f ? shadow_view_proj(l, world_bounds) : glm::mat4(1.0f);
    }
    if (!light_data.empty()) {
        glNamedBufferSubData(lights_ssbo.id(), 0, static_cast<GLsizeiptr>(light_data.size() * sizeof(gpu::light_block)),
                             light_data.data());
    }
}

const frame_stats& renderer::impl::render(int frame) {
    const view_matrices v = camera_matrices(s.view, frame, width, height);
    const bool sss_pass = m.scatters() && sss_visible(v.view_proj);

    // The reference is the converged integral: re-render it only when its inputs changed (camera pose, light
    // intensities; objects do not move in this scene model), else show the last result again.
    bool reuse_reference = false;
    if (m.type == method::kind::reference && sss_pass) {
        signature[0] = v.position.x; signature[1] = v.position.y; signature[2] = v.position.z;
        signature[3] = v.target.x; signature[4] = v.target.y; signature[5] = v.target.z;
        for (std::size_t i = 0; i < s.lights.size(); ++i) {
            const glm::vec3 e = s.lights[i].color * s.lights[i].intensity.at(frame) * light_scale[i];
            signature[6 + 3 * i] = e.x; signature[7 + 3 * i] = e.y; signature[8 + 3 * i] = e.z;
        }
        reuse_reference = reference_valid && signature == reference_signature;
    }
    update_frame(frame, v, sss_pass);
    for (timed_pass& p : passes) p.recorded = false;

    glBindBufferBase(GL_UNIFORM_BUFFER, EMCV_RENDER_FRAME, frame_ubo.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EMCV_RENDER_LIGHTS, lights_ssbo.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EMCV_RENDER_MATERIALS, materials_ssbo.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EMCV_RENDER_OBJECTS, objects_ssbo.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EMCV_RENDER_STATS, stats_ssbo.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EMCV_RENDER_TILES, tiles_ssbo.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EMCV_RENDER_KERNELS, kernels_ssbo.id());
    glBindVertexArray(vao.id());

    {  // G-buffer
        begin_pass(0);
        glBindFramebuffer(GL_FRAMEBUFFER, gbuffer_fbo.id());
        glViewport(0, 0, width, height);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        const GLuint zero_u[4] = {0u, 0u, 0u, 0u};
        const float far_depth = 1.0f;
        for (GLint i = 0; i < 5; ++i) {
            if (i == 3) glClearNamedFramebufferuiv(gbuffer_fbo.id(), GL_COLOR, i, zero_u);
            else glClearNamedFramebufferfv(gbuffer_fbo.id(), GL_COLOR, i, zero);
        }
        glClearNamedFramebufferfv(gbuffer_fbo.id(), GL_DEPTH, 0, &far_depth);
        gbuffer_program.use();
        draw_objects(true);
        end_pass(0);
    }
    if (!shadow_lights.empty()) {
        shadow_program.use();
        glViewport(0, 0, shadow_resolution, shadow_resolution);
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(1.5f, 2.0f);
        for (std::size_t k = 0; k < shadow_lights.size(); ++k) {
            if (!light_shines(s.lights[shadow_lights[k]], frame)) continue;  // dark this frame: lighting skips it
            begin_pass(1 + k);
            glBindFramebuffer(GL_FRAMEBUFFER, shadow_fbos[k].id());
            const float far_depth = 1.0f;
            glClearNamedFramebufferfv(shadow_fbos[k].id(), GL_DEPTH, 0, &far_depth);
            glBindBufferRange(GL_UNIFORM_BUFFER, EMCV_RENDER_PASS, pass_ubo.id(), GLintptr{pass_stride} * GLintptr(k),
                              sizeof(gpu::pass_block));
            draw_objects(false);
            end_pass(1 + k);
        }
        glDisable(GL_POLYGON_OFFSET_FILL);
    }
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);

    // Compute passes read the targets through samplers and write images.
    glBindTextureUnit(EMCV_RENDER_TEX_SHADOWS, shadow_maps.id());
    glBindTextureUnit(EMCV_RENDER_TEX_DEPTH, gb_depth.id());
    glBindTextureUnit(EMCV_RENDER_TEX_NORMAL, gb_normal.id());
    glBindTextureUnit(EMCV_RENDER_TEX_ALBEDO, gb_albedo.id());
    glBindTextureUnit(EMCV_RENDER_TEX_MATERIAL, gb_material.id());
    glBindTextureUnit(EMCV_RENDER_TEX_MOTION, gb_motion.id());
    glBindTextureUnit(EMCV_RENDER_TEX_DIFFUSE, lit_diffuse.id());
    glBindTextureUnit(EMCV_RENDER_TEX_SPECULAR, lit_specular.id());
    const GLuint groups_x = div_up(width, EMCV_RENDER_TILE_SIZE);
    const GLuint groups_y = div_up(height, EMCV_RENDER_TILE_SIZE);
    {
        begin_pass(slot_lighting);
        lighting_program.use();
        glBindImageTexture(EMCV_RENDER_IMG_DIFFUSE, lit_diffuse.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glBindImageTexture(EMCV_RENDER_IMG_SPECULAR, lit_specular.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glDispatchCompute(groups_x, groups_y, 1);
        image_barrier_for_reads();
        end_pass(slot_lighting);
    }
    if (sss_pass && !reuse_reference) {
        begin_pass(slot_tiles);
        const GLuint header[4] = {0u, 0u, 1u, 0u};  // no tiles yet: the dispatch pass writes x, y from w
        glNamedBufferSubData(tiles_ssbo.id(), 0, sizeof header, header);
        glClearNamedBufferData(stats_ssbo.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
        glClearTexImage(counts.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
        counts_dirty = true;
        tiles_program.use();
        glDispatchCompute(groups_x, groups_y, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        dispatch_program.use();
        glDispatchCompute(1, 1, 1);
        glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        end_pass(slot_tiles);

        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, tiles_ssbo.id());
        glBindImageTexture(EMCV_RENDER_IMG_COUNT, counts.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32UI);
        if (m.type == method::kind::separable) {
            separable_program.use();
            begin_pass(slot_sep_h);
            glBindTextureUnit(EMCV_RENDER_TEX_SSS_IN, lit_diffuse.id());
            glBindImageTexture(EMCV_RENDER_IMG_SSS_OUT, sss_temp.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
            glBindBufferRange(GL_UNIFORM_BUFFER, EMCV_RENDER_PASS, pass_ubo.id(),
                              GLintptr{pass_stride} * GLintptr(shadow_lights.size()), sizeof(gpu::pass_block));
            glDispatchComputeIndirect(0);
            image_barrier_for_reads();
            end_pass(slot_sep_h);
            begin_pass(slot_sep_v);
            glBindTextureUnit(EMCV_RENDER_TEX_SSS_IN, sss_temp.id());
            glBindImageTexture(EMCV_RENDER_IMG_SSS_OUT, sss_out.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
            glBindBufferRange(GL_UNIFORM_BUFFER, EMCV_RENDER_PASS, pass_ubo.id(),
                              GLintptr{pass_stride} * GLintptr(shadow_lights.size() + 1), sizeof(gpu::pass_block));
            glDispatchComputeIndirect(0);
            image_barrier_for_reads();
            end_pass(slot_sep_v);
        } else {
            if (adaptive_state) {
                begin_pass(slot_adaptive_samples);
                adaptive_state->record_samples();
                end_pass(slot_adaptive_samples);
            }
            begin_pass(slot_burley);
            burley_program.use();
            glBindImageTexture(EMCV_RENDER_IMG_SSS_OUT, sss_out.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
            glDispatchComputeIndirect(0);
            image_barrier_for_reads();
            glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
            end_pass(slot_burley);
            if (adaptive_state) {
                begin_pass(slot_adaptive_update);
                adaptive_state->record_update(sss_out.id());
                end_pass(slot_adaptive_update);
            }
        }
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    } else if (!sss_pass && counts_dirty) {
        glClearTexImage(counts.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);  // no samples this frame
        counts_dirty = false;
    }
    {
        begin_pass(slot_composite);
        composite_program.use();
        glBindTextureUnit(EMCV_RENDER_TEX_SSS_IN, sss_out.id());
        glBindImageTexture(EMCV_RENDER_IMG_LINEAR, linear_out.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glBindImageTexture(EMCV_RENDER_IMG_DISPLAY, display_out.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
        glDispatchCompute(groups_x, groups_y, 1);
        glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
        end_pass(slot_composite);
    }
    glBindVertexArray(0);
    if (adaptive_state) adaptive_state->end_frame(gb_depth.id(), gb_normal.id(), gb_material.id(), sss_pass);
    prev_view_proj = v.view_proj;
    has_previous = true;

    // Statistics: the GPU's reduction over SSS pixels (16 bytes read back).
    stats.frame = frame;
    stats.reference_reused = reuse_reference;
    if (!sss_pass) {
        stats.mean_spp = 0.0;
        stats.max_spp = 0;
        stats.sss_pixels = 0;
    } else if (reuse_reference) {
        stats.mean_spp = reference_mean_spp;
        stats.max_spp = reference_max_spp;
        stats.sss_pixels = reference_sss_pixels;
    } else {
        gpu::stats_block gpu_stats{};
        glGetNamedBufferSubData(stats_ssbo.id(), 0, sizeof gpu_stats, &gpu_stats);
        stats.sss_pixels = gpu_stats.sss_pixels;
        if (m.type == method::kind::separable) {
            stats.max_spp = gpu_stats.sss_pixels > 0 ? 2 * m.samples : 0;
            stats.mean_spp = stats.max_spp;
        } else {
            stats.max_spp = static_cast<int>(gpu_stats.sample_max);
            stats.mean_spp = gpu_stats.sss_pixels > 0 ? double(gpu_stats.sample_sum) / gpu_stats.sss_pixels : 0.0;
        }
        if (m.type == method::kind::reference) {
            reference_signature = signature;
            reference_valid = true;
            reference_mean_spp = stats.mean_spp;
            reference_max_spp = stats.max_spp;
            reference_sss_pixels = stats.sss_pixels;
        }
    }

    std::size_t n = 0;
    // Back to one entry per pass slot: an earlier frame may have recorded fewer passes (a reused reference)
    // and shrunk the list, and stats.passes[n++] below must stay in bounds (it was heap corruption at
    // light-off's switch, frame 31). Within the capacity reserved in the constructor: no allocation.
    stats.passes.resize(passes.size());
    stats.sss_ms = 0.0;
    stats.frame_ms = 0.0;
    for (timed_pass& p : passes) {
        if (o.timing_mode == timing::asynchronous) {
            while (const std::optional<double> ms = p.timer.pop_ms()) p.last_ms = *ms;
        }
        if (!p.recorded) continue;
        pass_time& t = stats.passes[n++];
        t.name = p.name;
        t.ms = p.last_ms;
        stats.frame_ms += p.last_ms;
        if (p.name.compare(0, 4, "sss-") == 0) stats.sss_ms += p.last_ms;
    }
    stats.passes.resize(n);
    return stats;
}

renderer::renderer(const scene& s, method m, render_options options)
    : p_(std::make_unique<impl>(s, m, std::move(options))) {}
renderer::~renderer() = default;
renderer::renderer(renderer&&) noexcept = default;
renderer& renderer::operator=(renderer&&) noexcept = default;

const frame_stats& renderer::render(int frame) { return p_->render(frame); }

void renderer::set_method(const method& m) {
    p_->m = m;
    p_->reference_valid = false;
    p_->upload_materials();  // separable kernels follow the tap count
    p_->make_adaptive_state();
}

const method& renderer::current_method() const { return p_->m; }

void renderer::set_light_scale(std::size_t light, float scale) {
    if (light >= p_->light_scale.size()) throw std::out_of_range("renderer: no light " + std::to_string(light));
    p_->light_scale[light] = scale;
}

namespace {

/// One channel of an integer texture as floats (R8UI or R32UI).
std::vector<std::uint32_t> read_uint_texture(GLuint texture, int width, int height, GLenum type) {
    const std::size_t count = std::size_t(width) * std::size_t(height);
    std::vector<std::uint32_t> values(count);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (type == GL_UNSIGNED_BYTE) {
        std::vector<std::uint8_t> bytes(count);
        glGetTextureImage(texture, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, static_cast<GLsizei>(count), bytes.data());
        std::copy(bytes.begin(), bytes.end(), values.begin());
    } else {
        glGetTextureImage(texture, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, static_cast<GLsizei>(count * 4), values.data());
    }
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    return values;
}

gl::float_image single_channel(int width, int height) {
    gl::float_image img;
    img.width = width;
    img.height = height;
    img.channels = 1;
    img.pixels.assign(std::size_t(width) * std::size_t(height), 0.0f);
    return img;
}

}  // namespace

gl::float_image renderer::display() const { return gl::read_texture_rgba32f(p_->display_out.id(), p_->width, p_->height); }
gl::float_image renderer::linear() const { return gl::read_texture_rgba32f(p_->linear_out.id(), p_->width, p_->height); }
gl::float_image renderer::diffuse_irradiance() const {
    return gl::read_texture_rgba32f(p_->lit_diffuse.id(), p_->width, p_->height);
}

gl::float_image renderer::sss_mask() const {
    const std::vector<std::uint32_t> codes = read_uint_texture(p_->gb_material.id(), p_->width, p_->height, GL_UNSIGNED_BYTE);
    gl::float_image img = single_channel(p_->width, p_->height);
    for (std::size_t i = 0; i < codes.size(); ++i) {
        img.pixels[i] = codes[i] != 0u && p_->s.materials[codes[i] - 1u].scatters() ? 1.0f : 0.0f;
    }
    return img;
}

gl::float_image renderer::sample_counts() const {
    const std::vector<std::uint32_t> n = read_uint_texture(p_->counts.id(), p_->width, p_->height, GL_UNSIGNED_INT);
    gl::float_image img = single_channel(p_->width, p_->height);
    std::transform(n.begin(), n.end(), img.pixels.begin(), [](std::uint32_t x) { return static_cast<float>(x); });
    return img;
}

GLuint renderer::display_texture() const { return p_->display_out.id(); }
gl::float_image renderer::cv_alpha() const {
    if (p_->adaptive_state) return p_->adaptive_state->alpha();
    gl::float_image img = single_channel(p_->width, p_->height);
    return img;
}
adaptive::history* renderer::adaptive_history() { return p_->adaptive_state ? &*p_->adaptive_state : nullptr; }
int renderer::width() const { return p_->width; }
int renderer::height() const { return p_->height; }

}  // namespace emcv::demo
