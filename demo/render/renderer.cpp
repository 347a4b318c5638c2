// SPDX-License-Identifier: MIT
// The SSS renderer (renderer.hpp): a scheduler. Resources are made once (resources.hpp); each frame the
// planner lists the passes (pass_list.hpp) and the renderer records exactly those, each through its module
// (passes/), inside a debug group and a timer, then reads back the GPU's sample statistics.
#include "renderer.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <optional>
#include <stdexcept>

#include "adaptive/history.hpp"
#include "tunables.hpp"
#include "frame_constants.hpp"
#include "gl/timestamps.hpp"
#include "passes/passes.hpp"
#include "render/bindings.h"
#include "resources.hpp"

namespace emcv::demo {

namespace {


constexpr int max_size = 8192;

render_options validated(render_options o) {
    if (o.width < 1 || o.height < 1 || o.width > max_size || o.height > max_size) {
        throw std::runtime_error("renderer: size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                                 " out of range (1.." + std::to_string(max_size) + " per side)");
    }
    if (!(o.exposure > 0.0f) || !std::isfinite(o.exposure)) throw std::runtime_error("renderer: exposure must be > 0");
    check_tunables(o.defines);
    return o;
}

/// Measured frames kept for take_times at most: a caller that never takes them (the window) holds no more.
constexpr std::size_t max_unclaimed_frames = 1024;

std::unique_ptr<gl::timestamp_source> make_timestamps(timing t) {
    return t == timing::gpu ? gl::make_gpu_timestamps() : gl::make_wall_timestamps();
}

}  // namespace

struct renderer::impl {
    scene s;
    method m;
    render_options o;
    shader_setup shaders;
    program_cache cache;  // every program of the passes and of the adaptive history
    pass_programs programs;
    gpu_resources res;
    std::optional<adaptive::history> history;  // the adaptive methods only (method table)
    frame_planner planner;
    frame_constants constants;
    std::vector<float> light_scale;
    std::vector<std::string> slot_names;  // timing tags: pass_id_count fixed slots, then one per shadow layer
    gl::pass_timestamps stamps;
    std::deque<frame_times> unclaimed;  // measured frames not yet taken (take_times)
    frame_stats stats;
    frame_stats held_reference;  // the reference's statistics, shown again while it reuses its result
    bool keeps_gbuffer = false;     // adaptive: the last frame updated the history, its G-buffer is the next's previous
    bool previous_gbuffer_usable = false;  // adaptive: the previous G-buffer's material marks pixels with a history
    bool resolved = false;  // the last frame ended with the resolve pass: resolved_display holds what is shown

    impl(const scene& sc, method me, render_options op)
        : s(sc), m(me), o(validated(std::move(op))), shaders(make_shader_setup(o)),
          cache(shaders.preprocess, shaders.shader_dir), programs(cache), res(make_gpu_resources(s, m, o.width, o.height)), planner(s, m, o.width, o.height, o.resolve, sampling_mode_of(o.defines), o.jitter), constants(s),
          light_scale(s.lights.size(), 1.0f), stamps(make_timestamps(o.timing_mode)) {
        prepare_pass_programs(programs, s, m, o.resolve);
        make_history(m);
        if (o.resolve == resolve_mode::taa) make_resolve_targets(res, !o.jitter);
        for (std::size_t id = 0; id < pass_id_count; ++id)
            slot_names.emplace_back(pass_base_name(static_cast<pass_id>(id)));
        for (std::size_t layer = 0; layer < res.shadow_lights.size(); ++layer)
            slot_names.push_back(pass_name(s, {pass_id::shadow, res.shadow_lights[layer], layer}));
    }

    /// A fresh history for method `next` (none for a method without one). Built before the old one goes: a
    /// program that does not compile leaves the renderer as it was.
    void make_history(const method& next) {
        std::optional<adaptive::history> made;
        if (is_adaptive(next)) made.emplace(next, o.width, o.height, cache);
        history = std::move(made);
        keeps_gbuffer = false;  // the next frame starts fresh
        if (history) {
            make_previous_gbuffer(res);
            previous_gbuffer_usable = true;  // perhaps another method's: forgotten before the next frame
        }
    }

    std::size_t slot_of(const planned_pass& p) const {
        return p.id == pass_id::shadow ? pass_id_count + p.layer : static_cast<std::size_t>(p.id);
    }

    /// Samples per SSS pixel from the GPU's reduction (16 bytes read back), or the held reference's.
    void collect_sample_stats(bool visible) {
        if (!visible) {
            stats.mean_spp = 0.0;
            stats.max_spp = 0;
            stats.sss_pixels = 0;
            return;
        }
        if (planner.reuses_result()) {
            stats.mean_spp = held_reference.mean_spp;
            stats.max_spp = held_reference.max_spp;
            stats.sss_pixels = held_reference.sss_pixels;
            return;
        }
        gpu::stats_block gpu_stats{};
        glGetNamedBufferSubData(res.stats_ssbo.id(), 0, sizeof gpu_stats, &gpu_stats);
        stats.sss_pixels = gpu_stats.sss_pixels;
        if (row_of(m).passes() == sss_passes::separable) {  // every SSS pixel takes 2 * taps
            stats.max_spp = gpu_stats.sss_pixels > 0 ? 2 * m.samples : 0;
            stats.mean_spp = stats.max_spp;
        } else {
            stats.max_spp = static_cast<int>(gpu_stats.sample_max);
            stats.mean_spp = gpu_stats.sss_pixels > 0 ? double(gpu_stats.sample_sum) / gpu_stats.sss_pixels : 0.0;
        }
        if (row_of(m).holds_result()) {
            held_reference.mean_spp = stats.mean_spp;
            held_reference.max_spp = stats.max_spp;
            held_reference.sss_pixels = stats.sss_pixels;
        }
    }

    /// Names and sums the frames whose stamps have arrived; the newest becomes stats.times.
    void absorb(std::vector<gl::timed_frame> measured) {
        for (gl::timed_frame& t : measured) {
            frame_times f;
            f.frame = t.frame;
            f.passes.resize(t.tags.size());
            for (std::size_t i = 0; i < t.tags.size(); ++i) {
                f.passes[i] = {slot_names.at(t.tags[i]), t.ms[i]};
                f.frame_ms += t.ms[i];
                // tags below pass_id_count are pass ids; the shadow layers' slots follow them
                if (t.tags[i] < pass_id_count && is_sss_pass(static_cast<pass_id>(t.tags[i]))) f.sss_ms += t.ms[i];
            }
            stats.times = f;
            unclaimed.push_back(std::move(f));
            if (unclaimed.size() > max_unclaimed_frames) unclaimed.pop_front();
        }
    }

    std::vector<frame_times> take_times(bool wait) {
        absorb(stamps.collect(wait));
        std::vector<frame_times> out(std::make_move_iterator(unclaimed.begin()), std::make_move_iterator(unclaimed.end()));
        unclaimed.clear();
        return out;
    }

    const frame_stats& render(int frame) {
        if (history) {
            // The last frame's G-buffer becomes the previous one (a swap, no copy), or, when it updated no
            // history, the previous one is marked unusable (once, not on every frame without SSS) so that every
            // pixel starts fresh.
            if (keeps_gbuffer) {
                swap_gbuffer(res);
                previous_gbuffer_usable = true;
            } else if (previous_gbuffer_usable) {
                forget_previous_gbuffer(res);
                previous_gbuffer_usable = false;
            }
        }
        const std::vector<planned_pass>& plan = planner.plan(frame, light_scale);
        const view_matrices& v = planner.view();
        const bool visible = planner.shows_sss();
        constants.upload(res, s, m, o, frame, v, visible, planner.scatters(), planner.resolves_sss_noise(), light_scale);
        const frame_context context{res, programs, s, m, history ? &*history : nullptr, frame,
                                    tiles_covering(o.width), tiles_covering(o.height),
                                    planner.scatters()};
        passes::bind_frame_resources(context);
        if (history) history->begin_frame(planner.planned_by_previous());
        // A stamp at every pass boundary (gl/timestamps.hpp): the wall clock finishes the GPU's work there, GPU
        // timestamps never wait.
        stamps.begin_frame(frame);
        resolved = false;
        for (const planned_pass& p : plan) {
            const std::size_t slot = slot_of(p);
            glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, slot_names[slot].c_str());
            passes::record(p, context);
            glPopDebugGroup();
            stamps.end_pass(slot);
            resolved = resolved || p.id == pass_id::resolve;
        }
        stamps.end_frame();
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
        glBindVertexArray(0);

        if (history) history->end_frame(visible);
        if (resolved) swap_resolve_history(res);
        keeps_gbuffer = history && visible;
        constants.end_frame(v);

        stats.frame = frame;
        stats.reference_reused = planner.reuses_result();
        collect_sample_stats(visible);
        absorb(stamps.collect(false));
        return stats;
    }
};

renderer::renderer(const scene& s, method m, render_options options)
    : p_(std::make_unique<impl>(s, m, std::move(options))) {}
renderer::~renderer() = default;
renderer::renderer(renderer&&) noexcept = default;
renderer& renderer::operator=(renderer&&) noexcept = default;

const frame_stats& renderer::render(int frame) { return p_->render(frame); }

std::vector<frame_times> renderer::take_times(bool wait) { return p_->take_times(wait); }

void renderer::set_method(const method& m) {
    // First the programs, which may not compile: then the renderer keeps its method (a program once built is
    // kept, which harms nothing).
    prepare_pass_programs(p_->programs, p_->s, m, p_->o.resolve);
    p_->make_history(m);
    p_->m = m;
    p_->planner = frame_planner(p_->s, m, p_->o.width, p_->o.height, p_->o.resolve, sampling_mode_of(p_->o.defines),
                                p_->o.jitter);
    upload_materials(p_->res, p_->s, m);  // separable kernels follow the tap count
    if (p_->o.resolve == resolve_mode::taa) forget_resolve_history(p_->res);  // another method's image
}

const method& renderer::current_method() const { return p_->m; }

void renderer::set_light_scale(std::size_t light, float scale) {
    if (light >= p_->light_scale.size()) throw std::out_of_range("renderer: no light " + std::to_string(light));
    p_->light_scale[light] = scale;
}

namespace {

/// One channel of an integer texture (R8UI or R32UI).
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

gl::float_image renderer::display() const { return gl::read_texture_rgba32f(p_->res.display_out.id(), width(), height()); }
gl::float_image renderer::linear() const { return gl::read_texture_rgba32f(p_->res.linear_out.id(), width(), height()); }
gl::float_image renderer::diffuse_irradiance() const {
    return gl::read_texture_rgba32f(p_->res.lit_diffuse.id(), width(), height());
}
gl::float_image renderer::scattered_irradiance() const {
    return gl::read_texture_rgba32f(p_->res.sss_out.id(), width(), height());
}
gl::float_image renderer::surface_albedo() const {
    return gl::read_texture_rgba32f(p_->res.gb_albedo.id(), width(), height());
}

gl::float_image renderer::sss_mask() const {
    const std::vector<std::uint32_t> codes = read_uint_texture(p_->res.gb_material.id(), width(), height(), GL_UNSIGNED_BYTE);
    gl::float_image img = single_channel(width(), height());
    for (std::size_t i = 0; i < codes.size(); ++i)
        img.pixels[i] = codes[i] != 0u && p_->s.materials[codes[i] - 1u].scatters() ? 1.0f : 0.0f;
    return img;
}

gl::float_image renderer::sample_counts() const {
    gl::float_image img = single_channel(width(), height());
    if (!p_->planner.shows_sss()) return img;  // no samples this frame
    // The SSS passes write the count of every pixel of the SSS tiles; the texture is never cleared (no
    // full-screen work per frame for a read-back), so the pixels that do not scatter read 0 here. A frame that
    // shows the reference's held result shows the counts it was made with.
    const std::vector<std::uint32_t> n = read_uint_texture(p_->res.counts.id(), width(), height(), GL_UNSIGNED_INT);
    const gl::float_image mask = sss_mask();
    for (std::size_t i = 0; i < n.size(); ++i) img.pixels[i] = mask.pixels[i] > 0.5f ? static_cast<float>(n[i]) : 0.0f;
    return img;
}

GLuint renderer::display_texture() const {
    return p_->resolved ? p_->res.resolved_display.id() : p_->res.display_out.id();
}
gl::float_image renderer::shown() const {
    return gl::read_texture_rgba32f(display_texture(), width(), height());
}
gl::float_image renderer::cv_alpha() const {
    if (p_->history) return p_->history->alpha();
    return single_channel(width(), height());
}
adaptive::history* renderer::adaptive_history() { return p_->history ? &*p_->history : nullptr; }
int renderer::width() const { return p_->res.width; }
int renderer::height() const { return p_->res.height; }

}  // namespace emcv::demo
