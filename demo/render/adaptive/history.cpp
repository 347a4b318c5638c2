// SPDX-License-Identifier: MIT
#include "history.hpp"

#include <cstddef>
#include <cstring>
#include <stdexcept>

#include <glm/gtc/packing.hpp>

#include <emcv/port/cv.h>

#include "adaptive/bindings.h"
#include "emcv/port/bindings.h"

#include "gl/debug.hpp"
#include "render/targets.hpp"
#include "render/tunables.hpp"

#include <string>

// Image units: every binding below the guaranteed minimum (NVIDIA has exactly 8), and the adaptive images apart
// from the burley pass's own (render/bindings.h), which stay bound across the adaptive samples pass.
static_assert(EMCV_ADAPTIVE_IMG_SAMPLES < EMCV_MAX_IMAGE_UNITS && EMCV_ADAPTIVE_IMG_HISTORY_A < EMCV_MAX_IMAGE_UNITS &&
              EMCV_ADAPTIVE_IMG_HISTORY_B < EMCV_MAX_IMAGE_UNITS);
static_assert(EMCV_ADAPTIVE_IMG_SAMPLES != EMCV_RENDER_IMG_SSS_OUT && EMCV_ADAPTIVE_IMG_SAMPLES != EMCV_RENDER_IMG_COUNT &&
              EMCV_ADAPTIVE_IMG_HISTORY_A != EMCV_RENDER_IMG_COUNT && EMCV_ADAPTIVE_IMG_HISTORY_B != EMCV_RENDER_IMG_COUNT &&
              EMCV_ADAPTIVE_IMG_HISTORY_A != EMCV_ADAPTIVE_IMG_SAMPLES && EMCV_ADAPTIVE_IMG_HISTORY_B != EMCV_ADAPTIVE_IMG_SAMPLES &&
              EMCV_ADAPTIVE_IMG_HISTORY_A != EMCV_ADAPTIVE_IMG_HISTORY_B);

// The adaptive burley pass also writes its output and count images: apart from the history's.
static_assert(EMCV_RENDER_IMG_SSS_OUT != EMCV_ADAPTIVE_IMG_SAMPLES && EMCV_RENDER_IMG_SSS_OUT != EMCV_ADAPTIVE_IMG_HISTORY_A &&
              EMCV_RENDER_IMG_SSS_OUT != EMCV_ADAPTIVE_IMG_HISTORY_B && EMCV_RENDER_IMG_COUNT != EMCV_ADAPTIVE_IMG_SAMPLES);

namespace emcv::demo::adaptive {

namespace {

/// History formats (include/emcv/port/history.h): moving stats one RGBA16F; the EMCM RGBA32F + RG32F.
GLenum format_a(history_layout l) { return l == history_layout::emcm2 ? GL_RGBA32F : GL_RGBA16F; }
constexpr GLenum format_b = GL_RG32F;

/// The shader options of the method's adaptive passes: the renderer's, plus the method's define.
history_layout checked_layout(const method& m) {
    const history_layout l = row_of(m).history();
    if (l == history_layout::none)
        throw std::invalid_argument("adaptive history: method " + m.name() + " keeps no history");
    return l;
}

}  // namespace

history::history(const method& m, int width, int height, const gl::preprocess_options& shaders,
                 const std::filesystem::path& shader_dir)
    : history(m, width, height, std::make_shared<program_cache>(shaders, shader_dir)) {}

history::history(const method& m, int width, int height, std::shared_ptr<program_cache> owned)
    : history(m, width, height, *owned) {
    owned_ = std::move(owned);
}

history::history(const method& m, int width, int height, program_cache& programs)
    : layout_(checked_layout(m)), budget_mode_(sampling_mode_of(programs.base().defines).budget),
      block_(static_cast<int>(tunable_value(programs.base().defines, "EMCV_HISTORY_BLOCK"))), programs_(&programs),
      defines_(row_of(m).shader_defines()) {
    if (width < 1 || height < 1) throw std::runtime_error("adaptive history: empty size");
    // One texel per K x K block (EMCV_HISTORY_BLOCK), the grid rounded up (module/emcv_adaptive_history.glsl, emcv_adaptive_grid).
    pixel_width_ = width;
    pixel_height_ = height;
    width_ = (width + block_ - 1) / block_;
    height_ = (height + block_ - 1) / block_;
    // The samples pass and its image are made where they run: in budget mode now, under a quality target only
    // if asked for (record_samples). The solve needs no method define: one program serves every method.
    if (budget_mode_) {
        make_samples_pass();
        solve_program_ = &programs_->compute("adaptive/budget_solve.comp.glsl");
    }
    burley_program_ = &programs_->compute("render/sss_burley.comp.glsl", defines_);
    // The variants a budget's frames switch between are built now, not on the frame that first takes one: a
    // still view's second frame, or its first frame that reuses a plan, would carry a shader build.
    const sampling_mode sampling = sampling_mode_of(programs.base().defines);
    if (budget_mode_ && sampling.plan_ahead) use_burley(burley_variant::plans_next);
    if (budget_mode_ && sampling.update_period > 1) use_burley(burley_variant::reuses_plan);
    // Zeroed: no histogram yet (the first frame's pixels have no variance and take B), lambda 0.
    budget_ = gl::buffer::create();
    const emcv::port::EmcvBudgetBlock empty{};
    glNamedBufferStorage(budget_.id(), sizeof empty, &empty, GL_DYNAMIC_STORAGE_BIT);
    for (int i = 0; i < 2; ++i) {
        a_[static_cast<std::size_t>(i)] = make_cleared_target(format_a(layout_), width_, height_);
        // The second texture exists only where the layout has one (the EMCM); the others allocate nothing more.
        if (layout_ == history_layout::emcm2) b_[static_cast<std::size_t>(i)] = make_cleared_target(format_b, width_, height_);
    }
}

emcv::port::EmcvBudgetBlock history::read_budget() const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // the passes' atomics and stores before the read-back
    emcv::port::EmcvBudgetBlock b{};
    glGetNamedBufferSubData(budget_.id(), 0, sizeof b, &b);
    return b;
}

void history::bind_previous() const {
    const std::size_t prev = 1 - static_cast<std::size_t>(current_);
    glBindTextureUnit(EMCV_ADAPTIVE_TEX_HISTORY_PREV_A, a_[prev].id());
    glBindTextureUnit(EMCV_ADAPTIVE_TEX_HISTORY_PREV_B, layout_ == history_layout::emcm2 ? b_[prev].id() : a_[prev].id());
}

void history::make_samples_pass() {
    samples_program_ = &programs_->compute("adaptive/samples.comp.glsl", defines_);
    samples_ = make_cleared_target(GL_R32UI, width_, height_);
}

void history::record_samples() {
    if (samples_program_ == nullptr) make_samples_pass();
    samples_program_->use();
    bind_previous();
    bind_for_update();  // this frame's history, the samples image and the budget block, as the burley pass reads them
    glDispatchComputeIndirect(0);
    // The burley pass reads the images, and under a budget the lambda the solve stores.
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    if (budget_mode_) solve_budget();
}

void history::solve_budget() {
    if (!budget_mode_) throw std::logic_error("adaptive history: only a budget has a histogram to solve");
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // every workgroup's histogram atomics before the solve reads
    solve_program_->use();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EMCV_ADAPTIVE_BUDGET, budget_.id());
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // lambda and the prior before the burley pass reads them
}

void history::bind_for_update() const {
    const std::size_t cur = static_cast<std::size_t>(current_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EMCV_ADAPTIVE_BUDGET, budget_.id());
    glBindImageTexture(EMCV_ADAPTIVE_IMG_HISTORY_A, a_[cur].id(), 0, GL_FALSE, 0, GL_READ_WRITE, format_a(layout_));
    if (layout_ == history_layout::emcm2)
        glBindImageTexture(EMCV_ADAPTIVE_IMG_HISTORY_B, b_[cur].id(), 0, GL_FALSE, 0, GL_READ_WRITE, format_b);
    glBindImageTexture(EMCV_ADAPTIVE_IMG_SAMPLES, samples_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
}

void history::use_burley(burley_variant variant) {
    // The budget's variants are built on first use, with their define added to the method's.
    const auto variant_program = [&](const gl::program*& program, const char* define, const char* what) {
        if (!budget_mode_) throw std::logic_error(std::string("adaptive history: only a budget ") + what);
        if (program == nullptr) {
            program_cache::defines variant_defines = defines_;
            variant_defines.emplace_back(define, "1");
            program = &programs_->compute("render/sss_burley.comp.glsl", variant_defines);
        }
        return program;
    };
    switch (variant) {
        case burley_variant::updates: burley_program_->use(); break;
        case burley_variant::plans_next:
            variant_program(burley_plan_next_program_, "EMCV_ADAPTIVE_PLAN_NEXT", "plans the next frame's counts")->use();
            break;
        case burley_variant::reuses_plan:
            variant_program(burley_reuse_program_, "EMCV_ADAPTIVE_REUSE_PLAN", "reuses a plan")->use();
            break;
    }
    bind_previous();
    bind_for_update();
}

void history::begin_frame(bool in_place) {
    // end_frame made the newest textures the previous ones; in place they are this frame's again.
    if (in_place) current_ = 1 - current_;
}

void history::end_frame(bool updated) {
    if (updated) current_ = 1 - current_;
}

std::vector<texel> history::read() const {
    // end_frame swapped: the newest history is the one the next frame reprojects from.
    const std::size_t cur = 1 - static_cast<std::size_t>(current_);
    const std::size_t count = std::size_t(width_) * std::size_t(height_);
    std::vector<glm::vec4> a(count);
    glGetTextureImage(a_[cur].id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(count * sizeof(glm::vec4)), a.data());
    std::vector<glm::vec4> b(count, glm::vec4(0.0f));
    if (layout_ == history_layout::emcm2)
        glGetTextureImage(b_[cur].id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(count * sizeof(glm::vec4)),
                          b.data());
    std::vector<texel> out(count);
    for (std::size_t i = 0; i < count; ++i) out[i] = {a[i], glm::vec2(b[i])};
    return out;
}

void history::write_previous(const std::vector<texel>& texels) {
    const std::size_t count = std::size_t(width_) * std::size_t(height_);
    if (texels.size() != count) throw std::invalid_argument("adaptive history: write_previous needs one texel per pixel");
    const std::size_t prev = 1 - static_cast<std::size_t>(current_);
    std::vector<glm::vec4> a(count), b(count);
    for (std::size_t i = 0; i < count; ++i) {
        a[i] = texels[i].a;
        b[i] = glm::vec4(texels[i].b, 0.0f, 0.0f);
    }
    glTextureSubImage2D(a_[prev].id(), 0, 0, 0, width_, height_, GL_RGBA, GL_FLOAT, a.data());
    if (layout_ == history_layout::emcm2) glTextureSubImage2D(b_[prev].id(), 0, 0, 0, width_, height_, GL_RGBA, GL_FLOAT, b.data());
}

gl::float_image history::alpha() const {
    gl::float_image img;
    img.width = pixel_width_;
    img.height = pixel_height_;
    img.channels = 1;
    img.pixels.assign(std::size_t(pixel_width_) * std::size_t(pixel_height_), 0.0f);
    if (layout_ != history_layout::emcm2) return img;
    const std::vector<texel> t = read();
    // Each pixel shows its block's coefficient (one texel per K x K pixels).
    for (int y = 0; y < pixel_height_; ++y)
        for (int x = 0; x < pixel_width_; ++x)
            img.pixels[std::size_t(y) * std::size_t(pixel_width_) + std::size_t(x)] = emcv::port::emcv_cv_coefficient(
                t[std::size_t(y / block_) * std::size_t(width_) + std::size_t(x / block_)].a.y,
                t[std::size_t(y / block_) * std::size_t(width_) + std::size_t(x / block_)].a.z);
    return img;
}

}  // namespace emcv::demo::adaptive
