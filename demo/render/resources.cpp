// SPDX-License-Identifier: MIT
// The renderer's GPU resources (resources.hpp).
#include "resources.hpp"

#include <algorithm>
#include <utility>
#include <cstring>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_inverse.hpp>

#include <emcv/port/sss.h>

#include "emcv/port/bindings.h"
#include "pass_list.hpp"
#include "render/bindings.h"
#include "separable_kernel.hpp"
#include "targets.hpp"

namespace emcv::demo {

namespace fs = std::filesystem;

GLuint tiles_covering(int pixels) {
    return static_cast<GLuint>((pixels + EMCV_RENDER_TILE_SIZE - 1) / EMCV_RENDER_TILE_SIZE);
}

namespace {

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

void validate(const scene& s) {
    for (const object& ob : s.objects) {
        if (ob.mesh < 0 || static_cast<std::size_t>(ob.mesh) >= s.meshes.size() || ob.material < 0 ||
            static_cast<std::size_t>(ob.material) >= s.materials.size()) {
            throw std::runtime_error("renderer: object '" + ob.name + "' names a missing mesh or material");
        }
    }
    if (s.materials.size() > 254) throw std::runtime_error("renderer: at most 254 materials (8-bit material ids)");
}

void upload_geometry(gpu_resources& r, const scene& s) {
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
    r.vertices = make_buffer(all_vertices.data(), all_vertices.size(), 0);
    r.indices = make_buffer(all_indices.data(), all_indices.size(), 0);
    std::vector<std::uint32_t> ids(s.objects.size());
    for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<std::uint32_t>(i);
    r.object_ids = make_buffer(ids.data(), ids.size(), 0);

    r.vao = gl::vertex_array::create();
    const GLuint vao = r.vao.id();
    glVertexArrayVertexBuffer(vao, 0, r.vertices.id(), 0, sizeof(vertex));
    glVertexArrayVertexBuffer(vao, 1, r.object_ids.id(), 0, sizeof(std::uint32_t));
    glVertexArrayBindingDivisor(vao, 1, 1);
    glVertexArrayElementBuffer(vao, r.indices.id());
    glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(vertex, position));
    glVertexArrayAttribFormat(vao, 1, 3, GL_FLOAT, GL_FALSE, offsetof(vertex, normal));
    glVertexArrayAttribFormat(vao, 2, 2, GL_FLOAT, GL_FALSE, offsetof(vertex, uv));
    glVertexArrayAttribIFormat(vao, 3, 1, GL_UNSIGNED_INT, 0);
    for (GLuint a = 0; a < 4; ++a) {
        glEnableVertexArrayAttrib(vao, a);
        glVertexArrayAttribBinding(vao, a, a == 3 ? 1u : 0u);
    }

    std::vector<gpu::object_block> object_data;
    for (std::size_t i = 0; i < s.objects.size(); ++i) {
        const object& ob = s.objects[i];
        object_data.push_back({ob.model, glm::inverseTranspose(ob.model), glm::ivec4(ob.material, 0, 0, 0)});
        const range& rg = ranges[static_cast<std::size_t>(ob.mesh)];
        const material& mat = s.materials[static_cast<std::size_t>(ob.material)];
        r.draws.push_back({static_cast<GLsizei>(rg.index_count), rg.first_index * sizeof(std::uint32_t),
                           static_cast<GLint>(rg.first_vertex), static_cast<GLuint>(i), mat.albedo_texture});
    }
    // Sorted by albedo map so the texture binding changes once per map (no needless state changes).
    std::stable_sort(r.draws.begin(), r.draws.end(),
                     [](const draw_call& a, const draw_call& b) { return a.albedo_map < b.albedo_map; });
    r.objects_ssbo = make_buffer(object_data.data(), object_data.size(), 0);
    r.world_bounds = scene_bounds(s);

    const float one[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    r.white = make_albedo_map(1, 1, one);
    for (const texture& t : s.textures) {
        if (t.width < 1 || t.height < 1 || t.rgba.size() != std::size_t(t.width) * std::size_t(t.height) * 4) {
            throw std::runtime_error("renderer: texture " + t.path.string() + " has no pixels");
        }
        r.albedo_maps.push_back(make_albedo_map(t.width, t.height, t.rgba.data()));
    }
}

void make_frame_targets(gpu_resources& r) {
    const int width = r.width, height = r.height;
    r.depth_buffer = make_target(GL_DEPTH_COMPONENT32F, width, height);
    r.gb_depth = make_target(GL_R32F, width, height);
    r.gb_normal = make_target(GL_RGBA16F, width, height);
    r.gb_albedo = make_target(GL_RGBA16F, width, height);
    r.gb_material = make_target(GL_R8UI, width, height);
    r.gb_motion = make_target(GL_RG16F, width, height);
    r.lit_diffuse = make_target(GL_RGBA16F, width, height);
    r.lit_specular = make_target(GL_RGBA16F, width, height);
    r.sss_out = make_target(GL_RGBA16F, width, height);
    r.sss_temp = make_target(GL_RGBA16F, width, height);
    r.counts = make_cleared_target(GL_R32UI, width, height);  // 0 for the methods that never write it
    r.linear_out = make_target(GL_RGBA16F, width, height);
    r.display_out = make_target(GL_RGBA8, width, height);

    r.gbuffer_fbo = gl::framebuffer::create();
    const GLuint targets[5] = {r.gb_depth.id(), r.gb_normal.id(), r.gb_albedo.id(), r.gb_material.id(), r.gb_motion.id()};
    GLenum draw_buffers[5];
    for (GLuint i = 0; i < 5; ++i) {
        glNamedFramebufferTexture(r.gbuffer_fbo.id(), GL_COLOR_ATTACHMENT0 + i, targets[i], 0);
        draw_buffers[i] = GL_COLOR_ATTACHMENT0 + i;
    }
    glNamedFramebufferDrawBuffers(r.gbuffer_fbo.id(), 5, draw_buffers);
    glNamedFramebufferTexture(r.gbuffer_fbo.id(), GL_DEPTH_ATTACHMENT, r.depth_buffer.id(), 0);
    if (glCheckNamedFramebufferStatus(r.gbuffer_fbo.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        throw std::runtime_error("renderer: the G-buffer framebuffer is incomplete on this GL implementation");
    }
}

void make_shadow_maps(gpu_resources& r, const scene& s) {
    r.shadow_lights = shadow_casters(s);
    GLuint array_id = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &array_id);
    r.shadow_maps = gl::texture_2d(array_id);
    const int side = r.shadow_lights.empty() ? 1 : shadow_resolution;
    glTextureStorage3D(array_id, 1, GL_DEPTH_COMPONENT32F, side, side,
                       static_cast<GLsizei>(std::max<std::size_t>(r.shadow_lights.size(), 1)));
    glTextureParameteri(array_id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(array_id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(array_id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(array_id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(array_id, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(array_id, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    for (std::size_t k = 0; k < r.shadow_lights.size(); ++k) {
        gl::framebuffer fbo = gl::framebuffer::create();
        glNamedFramebufferTextureLayer(fbo.id(), GL_DEPTH_ATTACHMENT, array_id, 0, static_cast<GLint>(k));
        glNamedFramebufferDrawBuffer(fbo.id(), GL_NONE);
        if (glCheckNamedFramebufferStatus(fbo.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            throw std::runtime_error("renderer: a shadow-map framebuffer is incomplete on this GL implementation");
        }
        r.shadow_fbos.push_back(std::move(fbo));
    }
}

/// Per-pass constants: one range per shadow layer (its light), then the separable passes' directions.
void make_pass_constants(gpu_resources& r) {
    glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &r.pass_stride);
    r.pass_stride = std::max<GLint>(r.pass_stride, static_cast<GLint>(sizeof(gpu::pass_block)));
    const std::size_t stride = static_cast<std::size_t>(r.pass_stride);
    std::vector<std::uint8_t> bytes(stride * (r.shadow_lights.size() + 2), 0);
    for (std::size_t k = 0; k < r.shadow_lights.size(); ++k) {
        const gpu::pass_block b{glm::ivec4(static_cast<int>(r.shadow_lights[k]), 0, 0, 0), glm::vec4(0.0f)};
        std::memcpy(bytes.data() + k * stride, &b, sizeof b);
    }
    for (int direction = 0; direction < 2; ++direction) {
        const gpu::pass_block b{direction == 0 ? glm::ivec4(1, 0, 0, 0) : glm::ivec4(0, 1, 0, 0), glm::vec4(0.0f)};
        std::memcpy(bytes.data() + r.separable_slot(direction) * stride, &b, sizeof b);
    }
    r.pass_ubo = make_buffer(bytes.data(), bytes.size(), 0);
}

}  // namespace

shader_setup make_shader_setup(const render_options& o) {
    shader_setup out;
    out.shader_dir = gl::shader_source_dir(o.shader_dir, "EMCV_SHADER_DIR", EMCV_SHADER_DIR);
    const fs::path include_dir = gl::shader_source_dir(o.include_dir, "EMCV_INCLUDE_DIR", EMCV_INCLUDE_DIR);
    out.preprocess.include_dirs = {out.shader_dir, include_dir};
    out.preprocess.defines = o.defines;
    return out;
}

void prepare_pass_programs(pass_programs& out, const scene& s, const method& m, resolve_mode resolve) {
    pass_programs p = out;  // set only once every program has compiled: a failure leaves `out` as it was
    program_cache& cache = *p.cache;
    p.gbuffer.program = &cache.graphics("render/gbuffer.vert.glsl", "render/gbuffer.frag.glsl");
    p.shadow.program = shadow_casters(s).empty() ? nullptr
                                                 : &cache.graphics("render/shadow.vert.glsl", "render/shadow.frag.glsl");
    p.lighting.program = &cache.compute("render/lighting.comp.glsl");
    // The adaptive methods' burley program is their history's (adaptive::history), built with their define.
    p.burley.program = row_of(m).passes() == sss_passes::burley
                           ? &cache.compute("render/sss_burley.comp.glsl", row_of(m).shader_defines())
                           : nullptr;
    p.separable.program =
        row_of(m).passes() == sss_passes::separable ? &cache.compute("render/sss_separable.comp.glsl") : nullptr;
    p.composite.program = &cache.compute("render/composite.comp.glsl");
    p.resolve.program = resolve == resolve_mode::taa ? &cache.compute("render/resolve.comp.glsl") : nullptr;
    out = p;
}

void gpu_resources::draw_objects(bool with_albedo_maps) const {
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

void make_previous_gbuffer(gpu_resources& r) {
    if (r.prev_gb_material.id() != 0) return;
    r.prev_gb_depth = make_cleared_target(GL_R32F, r.width, r.height);
    r.prev_gb_normal = make_cleared_target(GL_RGBA16F, r.width, r.height);
    r.prev_gb_material = make_cleared_target(GL_R8UI, r.width, r.height);  // 0 = background: every pixel fresh
}

void make_resolve_targets(gpu_resources& r, bool guide) {
    r.resolve_history = make_cleared_target(GL_RGBA32F, r.width, r.height);
    r.resolve_history_previous = make_cleared_target(GL_RGBA32F, r.width, r.height);  // depth 0: no history
    r.resolved_display = make_target(GL_RGBA8, r.width, r.height);
    if (!guide) return;
    r.resolve_guide = make_cleared_target(GL_RGBA16F, r.width, r.height);
    r.resolve_guide_previous = make_cleared_target(GL_RGBA16F, r.width, r.height);
}

void swap_resolve_history(gpu_resources& r) {
    std::swap(r.resolve_history, r.resolve_history_previous);
    std::swap(r.resolve_guide, r.resolve_guide_previous);
}

void forget_resolve_history(gpu_resources& r) {
    glClearTexImage(r.resolve_history_previous.id(), 0, GL_RED, GL_FLOAT, nullptr);
}

void swap_gbuffer(gpu_resources& r) {
    std::swap(r.gb_depth, r.prev_gb_depth);
    std::swap(r.gb_normal, r.prev_gb_normal);
    std::swap(r.gb_material, r.prev_gb_material);
    // The attachments of make_frame_targets: 0 depth, 1 normal, 3 material.
    glNamedFramebufferTexture(r.gbuffer_fbo.id(), GL_COLOR_ATTACHMENT0, r.gb_depth.id(), 0);
    glNamedFramebufferTexture(r.gbuffer_fbo.id(), GL_COLOR_ATTACHMENT1, r.gb_normal.id(), 0);
    glNamedFramebufferTexture(r.gbuffer_fbo.id(), GL_COLOR_ATTACHMENT3, r.gb_material.id(), 0);
}

void forget_previous_gbuffer(gpu_resources& r) {
    glClearTexImage(r.prev_gb_material.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
}

gpu_resources make_gpu_resources(const scene& s, const method& m, int width, int height) {
    validate(s);
    gpu_resources r;
    r.width = width;
    r.height = height;
    upload_geometry(r, s);
    make_frame_targets(r);
    make_shadow_maps(r, s);
    upload_materials(r, s, m);
    make_pass_constants(r);
    r.frame_ubo = make_dynamic_buffer(sizeof(gpu::frame_block));
    r.lights_ssbo = make_dynamic_buffer(sizeof(gpu::light_block) * std::max<std::size_t>(s.lights.size(), 1));
    r.stats_ssbo = make_dynamic_buffer(sizeof(gpu::stats_block));
    const std::size_t tile_count =
        std::size_t{tiles_covering(width)} * tiles_covering(height);
    r.tiles_ssbo = make_dynamic_buffer(16 + 4 * tile_count);
    return r;
}

void upload_materials(gpu_resources& r, const scene& s, const method& m) {
    const bool separable = row_of(m).passes() == sss_passes::separable;
    std::vector<gpu::material_block> material_data;
    std::vector<glm::vec4> kernel_taps(std::max<std::size_t>(s.materials.size(), 1) * EMCV_RENDER_MAX_SEPARABLE_TAPS,
                                       glm::vec4(0.0f));
    for (std::size_t i = 0; i < s.materials.size(); ++i) {
        const material& mat = s.materials[i];
        gpu::material_block b{};
        b.albedo = glm::vec4(mat.albedo, mat.scatters() ? float(EMCV_RENDER_MATERIAL_SSS) : float(EMCV_RENDER_MATERIAL_DIFFUSE));
        b.mean_free_path = glm::vec4(mat.mean_free_path_mm, 0.0f);
        b.specular = glm::vec4(mat.specular, mat.roughness, 0.0f, 0.0f);
        if (mat.scatters() && separable) {
            const glm::vec3 d = emcv::port::emcv_sss_shape_distance(mat.mean_free_path_mm, mat.albedo);
            const separable_kernel k = make_separable_kernel(d, m.samples);
            b.separable = glm::vec4(k.half_width_mm, float(m.samples), 0.0f, 0.0f);
            std::copy(k.taps.begin(), k.taps.end(),
                      kernel_taps.begin() + static_cast<std::ptrdiff_t>(i * EMCV_RENDER_MAX_SEPARABLE_TAPS));
        }
        material_data.push_back(b);
    }
    r.materials_ssbo = make_buffer(material_data.data(), material_data.size(), 0);
    r.kernels_ssbo = make_buffer(kernel_taps.data(), kernel_taps.size(), 0);
}

}  // namespace emcv::demo
