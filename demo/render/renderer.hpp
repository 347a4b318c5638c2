// SPDX-License-Identifier: MIT
// emcv::demo renderer: the SSS renderer's public API (what emcv-demo and the tests code against).
//
// Data flows one way: scene (demo/scene/scene.hpp) -> pass list (pass_list.hpp, planned from the scene every
// frame) -> passes (passes/, one module each) -> images + frame_stats. The method table (method.hpp) says
// which SSS passes a method records and whether it keeps a history; docs/architecture.md draws the whole.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "frame_stats.hpp"
#include "gl/gl.hpp"
#include "gl/image_io.hpp"
#include "method.hpp"
#include "pass_list.hpp"
#include "render_options.hpp"
#include "scene/scene.hpp"

namespace emcv::demo {

namespace adaptive {
class history;  // demo/render/adaptive/history.hpp
}

/// The SSS renderer. Needs a current OpenGL 4.5 core context for its whole lifetime (demo/gl/context.hpp).
/// All GPU resources are created in the constructor, except timestamp queries, whose ring grows while the
/// GPU is more frames behind than ever before (gl/timestamps.hpp).
class renderer {
public:
    /// Uploads the scene's meshes and textures and builds the programs. Throws std::runtime_error (or
    /// gl::shader_error) naming the problem: a bad size, a missing shader, a compile error.
    renderer(const scene& s, method m, render_options options);
    ~renderer();
    renderer(renderer&&) noexcept;
    renderer& operator=(renderer&&) noexcept;
    renderer(const renderer&) = delete;
    renderer& operator=(const renderer&) = delete;

    /// Records and runs exactly the passes frame_planner::plan lists for this frame. Frames are rendered in
    /// increasing order (motion vectors and reference reuse compare with the previous call).
    /// Returns this frame's statistics (a reference to the renderer's own, reused every frame), with the
    /// newest measured frame's pass times.
    const frame_stats& render(int frame);
    /// Every measured frame's pass times not taken before, oldest first, each frame once: under the wall clock
    /// a frame is measured when render returns; under GPU timestamps once the GPU has written its stamps.
    /// `wait`: also wait for every rendered frame's (end of a run). The newest 1024 are kept for a caller that
    /// takes them late.
    std::vector<frame_times> take_times(bool wait);

    /// Switches the method (window keys); histories and the held reference are reset.
    void set_method(const method& m);
    const method& current_method() const;
    /// Multiplies light i's intensity curve (window keys toggle lights with 0 / 1). Default 1.
    void set_light_scale(std::size_t light, float scale);

    /// Tonemapped, sRGB-encoded RGBA in [0, 1] (alpha 1): what a PNG holds and what PSNR compares.
    gl::float_image display() const;
    /// Linear HDR RGBA radiance before the tonemap (for EXR).
    gl::float_image linear() const;
    /// One channel: 1 where the pixel's material scatters, 0 elsewhere (background included).
    gl::float_image sss_mask() const;
    /// One channel: samples taken at each pixel in the last frame (0 outside SSS pixels).
    gl::float_image sample_counts() const;
    /// Linear RGBA diffuse irradiance without albedo, before scattering (the lighting pass's output).
    gl::float_image diffuse_irradiance() const;
    /// Linear RGBA diffuse irradiance after scattering at the SSS pixels (the SSS passes' output; what the
    /// adaptive methods track as f). Meaningful at SSS pixels of a frame whose SSS passes ran.
    gl::float_image scattered_irradiance() const;
    /// Linear RGBA surface albedo with its texture (the G-buffer's).
    gl::float_image surface_albedo() const;
    /// cv: the control-variate coefficient alpha = C_fG / C_GG per pixel from the history (heatmap); zeros for
    /// the other methods.
    gl::float_image cv_alpha() const;
    /// The adaptive methods' history (spvg, cv, cv-notex; nullptr otherwise): read back, poisoned by tests.
    adaptive::history* adaptive_history();
    /// What the last frame shows: its temporal resolve when the frame ran one (render_options::resolve taa,
    /// every method but the reference), else display(). Same encoding as display().
    gl::float_image shown() const;
    /// The texture of shown() (RGBA8 sRGB-encoded values, width x height), for the window to blit.
    GLuint display_texture() const;

    int width() const;
    int height() const;

private:
    struct impl;
    std::unique_ptr<impl> p_;
};

}  // namespace emcv::demo
