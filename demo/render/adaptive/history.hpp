// SPDX-License-Identifier: MIT
// emcv::demo::adaptive::history — the GPU side of the adaptive methods spvg, cv and cv-notex: their per-pixel
// history textures (ping-pong), in budget mode the per-pixel variance texture the samples pass hands the burley
// pass, the budget block, and the method's programs (the renderer's previous G-buffer serves the reprojection
// test):
//   adaptive-samples  budget mode, before sss-burley: reproject + validate last frame's history, write the
//                     per-sample variance, added to the sigma histogram, from which a one-workgroup solve
//                     solves the scale of N = clamp(lambda sigma, ...) (include/emcv/port/budget.h). Built on
//                     first use: under a quality target the renderer never records it (tests do, for its N).
//   sss-burley        the renderer's burley pass built with the method's define: N per pixel (under a quality
//                     target planned by the pass itself from the reprojected history, module/emcv_adaptive_plan.glsl;
//                     under a budget from sigma and lambda), then this frame's (f, G) pushed into the history
//                     as a batch of N; under a budget, when the next frame shows the same view, its variant
//                     then plans the next frame as adaptive-samples would, and that frame records no samples
//                     pass (its history updated in place)
// Layouts and choices: include/emcv/port/history.h and docs/renderer.md. Created only for an adaptive
// method, so the other methods allocate nothing of this.
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "gl/handles.hpp"
#include "gl/image_io.hpp"
#include "gl/program.hpp"
#include "render/method.hpp"
#include "render/pass_list.hpp"
#include "render/program_cache.hpp"

#include <emcv/port/budget.h>

namespace emcv::demo::adaptive {

/// One pixel's stored history as read back: a = the first texture (spvg/cv-notex: (mean, var / target,
/// count, 0); cv: (C_ff, C_fG, C_GG, count)), b = the second (emcm2: (mean_f, mean_G)), zero otherwise.
struct texel {
    glm::vec4 a{0.0f};
    glm::vec2 b{0.0f};
};

class history {
public:
    /// Allocates the textures of the method's history layout (cleared: every pixel starts fresh) and takes
    /// the method's programs from `programs` (the renderer's cache, built with the row's shader_defines()): its
    /// burley pass (render/sss_burley.comp.glsl, which then takes N per pixel and updates the history after
    /// sampling) and, in budget mode, the adaptive-samples pass and the solve (adaptive/). The cache must outlive
    /// the history. Throws gl::shader_error or std::runtime_error naming the problem, std::invalid_argument for a
    /// method that keeps no history.
    history(const method& m, int width, int height, program_cache& programs);
    /// The same with a cache of its own over `shaders` and `shader_dir` (tests).
    history(const method& m, int width, int height, const gl::preprocess_options& shaders,
            const std::filesystem::path& shader_dir);

    history_layout layout() const noexcept { return layout_; }
    /// Whether the shader options select budget mode (sampling_mode_of their defines).
    bool budget_mode() const noexcept { return budget_mode_; }

    /// The budget block as the last solve left it (lambda, planned total); tests and diagnostics.
    emcv::port::EmcvBudgetBlock read_budget() const;

    /// The adaptive-samples pass (built on the first call). Expects what the renderer's SSS passes expect bound
    /// (frame UBO, materials, tile list as the GL_DISPATCH_INDIRECT_BUFFER, G-buffer and motion textures at
    /// their render slots), and the previous frame's depth, normal and material at EMCV_ADAPTIVE_TEX_PREV_*
    /// (the renderer's, which ping-pong with its G-buffer).
    /// Writes the variance (under a quality target: N, which the burley pass plans alike) into the samples
    /// image; in budget mode the solve dispatch after it (solve_budget) solves lambda into the budget block. The renderer records
    /// it in budget mode only.
    void record_samples();
    /// Budget mode: the one-workgroup solve of the histogram that the pass just dispatched added to
    /// (adaptive/budget_solve.comp.glsl): record_samples runs it itself, the renderer after a burley pass that
    /// planned the next frame. It orders itself after that pass's atomics, and the burley pass that spends
    /// lambda after it.
    void solve_budget();
    /// Makes the method's burley program current and binds what it reads and updates besides the burley
    /// pass's own outputs: last frame's history (which a quality target's burley pass reprojects, through the
    /// previous G-buffer the caller binds as for record_samples), this frame's history images, the samples image
    /// and the budget block. `plans_next` (budget mode): the program built with EMCV_ADAPTIVE_PLAN_NEXT, which
    /// after its update also plans the next frame's counts as that frame's samples pass would for the same view
    /// (sss_burley.comp.glsl, plan_next_frame); `reuses_plan` (budget mode): the one built with
    /// EMCV_ADAPTIVE_REUSE_PLAN, which samples with the counts the last update planned and writes no history. A
    /// budget's variants are built with the history (the constructor), the others on first use.
    void use_burley(burley_variant variant = burley_variant::updates);
    /// Start of every frame of the method: `in_place` when the last frame's burley pass planned this one
    /// (frame_planner::planned_by_previous): no samples pass copies the history into this frame's textures, so
    /// this frame's are the newest, updated where they are.
    void begin_frame(bool in_place);
    /// Binds this frame's history images, the samples image and the budget block at their adaptive slots
    /// (record_samples, use_burley; tests that run the history update on given values with a probe program).
    void bind_for_update() const;
    /// End of every frame of the method: after a frame that updated the history (`updated`), the next one
    /// reprojects from it. The caller keeps the matching G-buffer (previous depth, normal, material) or, after
    /// a frame without SSS pass, marks it unusable (material 0), so the next frame starts fresh everywhere.
    void end_frame(bool updated);

    /// The samples image (0 under a quality target until record_samples made it: the burley pass plans N itself).
    GLuint samples_texture() const noexcept { return samples_.id(); }

    /// The block grid's size (EMCV_HISTORY_BLOCK = K: the viewport divided by K, rounded up), the size of the
    /// history and samples images and of what read() returns.
    int grid_width() const noexcept { return width_; }
    int grid_height() const noexcept { return height_; }

    /// The newest history (after the last end_frame: what the next frame reprojects from), read back, one texel
    /// per block in rows of grid_width().
    std::vector<texel> read() const;
    /// Overwrites that history (tests: a poisoned state).
    void write_previous(const std::vector<texel>& texels);
    /// cv: alpha = C_fG / C_GG per pixel, its block's (port's guarded coefficient); 0 for the other methods.
    gl::float_image alpha() const;

private:
    history(const method& m, int width, int height, std::shared_ptr<program_cache> owned);
    /// Last frame's history textures at EMCV_ADAPTIVE_TEX_HISTORY_PREV_* (the reprojection's source).
    void bind_previous() const;
    /// Builds the samples program and allocates the samples image it writes (budget mode, or a test's first
    /// record_samples under a quality target).
    void make_samples_pass();

    history_layout layout_;
    bool budget_mode_;
    int block_;           // EMCV_HISTORY_BLOCK: pixels per texel side
    int pixel_width_ = 0, pixel_height_ = 0;  // the viewport
    int width_ = 0, height_ = 0;              // the block grid: one texel per block
    std::shared_ptr<program_cache> owned_;  // the tests' constructor's own cache; the renderer passes its own
    program_cache* programs_;
    program_cache::defines defines_;  // the method's (method_row::shader_defines)
    const gl::program* samples_program_ = nullptr;
    const gl::program* burley_program_ = nullptr;
    const gl::program* burley_plan_next_program_ = nullptr;
    const gl::program* burley_reuse_program_ = nullptr;
    const gl::program* solve_program_ = nullptr;
    gl::buffer budget_;  // EmcvBudgetBlock: allocated in every mode (the passes declare it), used in budget mode
    std::array<gl::texture_2d, 2> a_, b_;  // ping-pong: [current_] is this frame's
    int current_ = 0;
    gl::texture_2d samples_;
};

}  // namespace emcv::demo::adaptive
