// SPDX-License-Identifier: MIT
// emcv::demo renderer: the SSS renderer's public API (what emcv-demo and the tests code against).
//
// Data flows one way: scene (demo/scene/scene.hpp) -> pass list (rebuilt from the scene every frame) -> GPU
// passes -> images + frame_stats. The frame, in order (each pass recorded only when the scene calls for it):
//   gbuffer          linear view depth R32F, normal, albedo, material id, motion (previous frame's camera)
//   shadow:<light>   one per light with casts_shadow (directional: orthographic fitted to the scene bounds;
//                    spot: perspective; point lights never cast, see pass_list)
//   lighting         diffuse irradiance without albedo (RGBA16F) kept apart from specular GGX (RGBA16F)
//   sss-tiles        8x8 tiles holding an SSS pixel, appended on the GPU + indirect dispatch arguments
//   sss-burley | sss-separable-h, sss-separable-v    over the SSS tiles only (indirect dispatch)
//   composite        post-scatter albedo * scattered (or unscattered) diffuse + specular, tonemap, sRGB
// "sss-tiles" and the SSS passes are not recorded at all for `diffuse`, for a scene with no SSS material, or
// when every SSS object lies outside the view frustum (decided on the CPU from the scene, pass_list).
//
// Timing: with timing::per_frame (headless evaluation, the default) each pass is bracketed by glFinish and
// timed on the steady clock, so frame_stats holds this frame's times (on llvmpipe, whose GL_TIME_ELAPSED
// queries miss compute dispatches, the only correct measure). With timing::asynchronous (interactive window)
// each pass has a GPU timer ring (demo/gl/timer.hpp) and render() never waits: frame_stats holds the newest
// finished measurement of each pass (a few frames old), or 0 before the first one is ready.
// frame_ms is the sum of the frame's pass times (GL_TIME_ELAPSED queries cannot nest, and every GPU command
// of a frame is inside one pass); sss_ms is the sum of the sss-* passes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gl/gl.hpp"
#include "gl/image_io.hpp"
#include "scene/scene.hpp"

namespace emcv::demo {

namespace adaptive {
class history;  // demo/render/adaptive/history.hpp
}

/// A scattering method, as named on the command line (`--method`).
struct method {
    enum class kind { diffuse, burley, separable, reference, spvg, cv, cv_notex };
    kind type = kind::diffuse;
    /// burley: samples per SSS pixel (1..1024); separable: taps (11, 17 or 25); reference: samples per pixel
    /// (>= 1024 unless a test asks for fewer, see make_reference); 0 for the others.
    int samples = 0;

    /// "diffuse", "burley-16", "separable-17", "reference", "spvg", "cv", "cv-notex".
    std::string name() const;
    bool scatters() const { return type != kind::diffuse; }
    bool operator==(const method& o) const { return type == o.type && samples == o.samples; }
    bool operator!=(const method& o) const { return !(*this == o); }
};

/// Default sample counts.
inline constexpr int default_separable_taps = 17;
inline constexpr int default_reference_samples = 1024;

/// "diffuse", "burley-N" (N in 1..1024), "separable" (17 taps), "separable-11|17|25", "reference"
/// (1024 samples), "spvg", "cv", "cv-notex"; nullopt for anything else.
std::optional<method> parse_method(std::string_view text);

/// Every implemented method, in summary order: diffuse, burley-16, separable-17, reference, spvg, cv,
/// cv-notex. What `--method all` renders.
std::vector<method> all_methods();

/// The reference with an explicit sample count (tests: convergence against a 4x-sample render).
method make_reference(int samples);

enum class tonemap_operator { aces, reinhard };
enum class timing { per_frame, asynchronous };

struct render_options {
    int width = 128;
    int height = 128;
    std::uint32_t seed = 1;  ///< decorrelates the per-pixel, per-frame sample rotations
    /// Draw Burley radii with SPVG's approximate inverse CDF (port/burley.h) instead of the exact one; the
    /// exact pdf is evaluated either way. Applies to burley-N, reference and the adaptive methods.
    bool approximate_inverse_cdf = false;
    tonemap_operator tonemap = tonemap_operator::aces;
    float exposure = 1.0f;  ///< linear radiance is multiplied by this before the tonemap
    timing timing_mode = timing::per_frame;
    /// Where the GLSL passes and the port headers are read from at run time. Empty: $EMCV_SHADER_DIR /
    /// $EMCV_INCLUDE_DIR when set, else the source tree (compile definitions of emcv_demo_render).
    std::filesystem::path shader_dir;
    std::filesystem::path include_dir;
};

struct pass_time {
    std::string name;
    double ms = 0.0;
};

struct frame_stats {
    int frame = 0;
    double sss_ms = 0.0;    ///< sum of the sss-* passes (0 when none was recorded)
    double frame_ms = 0.0;  ///< sum of every pass of the frame
    /// Samples per SSS pixel that made this frame's image (burley-N: N; separable: 2 * taps; reference:
    /// its count, also on frames that reuse it; diffuse: 0). Counted on the GPU over the SSS pixels.
    double mean_spp = 0.0;
    int max_spp = 0;
    std::size_t sss_pixels = 0;      ///< visible pixels with a scattering material (0 if no SSS pass ran)
    bool reference_reused = false;   ///< reference: inputs unchanged, last frame's result shown again
    std::vector<pass_time> passes;   ///< in recording order, named as in pass_list
};

/// The passes the frame records for this scene, method and frame, in order (what `--print-passes` prints):
/// "gbuffer", "shadow:<light name>" per light with casts_shadow (point lights are skipped: they do not cast
/// in this renderer), "lighting", then, only if the method scatters and an SSS object can be visible,
/// "sss-tiles" and "sss-burley" or "sss-separable-h", "sss-separable-v", and finally "composite".
/// width/height give the aspect of the view frustum used for the visibility test.
std::vector<std::string> pass_list(const scene& s, const method& m, int frame, int width, int height);

/// True when some object with a scattering material intersects the view frustum at this frame (bounding
/// sphere of its transformed mesh against the six planes).
bool sss_possibly_visible(const scene& s, int frame, int width, int height);

/// The SSS renderer. Needs a current OpenGL 4.5 core context for its whole lifetime (demo/gl/context.hpp).
/// All GPU resources are created in the constructor; render() allocates nothing.
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

    /// Records and runs the frame's pass list. Frames are rendered in increasing order (motion vectors and
    /// reference reuse compare with the previous call).
    /// Returns this frame's statistics (a reference to the renderer's own, reused every frame: no allocation).
    const frame_stats& render(int frame);

    /// Switches the method (window keys); histories and the cached reference are reset.
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
    /// cv: the control-variate coefficient alpha = C_fG / C_GG per pixel from the history (heatmap); zeros for
    /// the other methods.
    gl::float_image cv_alpha() const;
    /// The adaptive methods' history (spvg, cv, cv-notex; nullptr otherwise): read back, poisoned by tests.
    adaptive::history* adaptive_history();
    /// The display texture (RGBA8 sRGB-encoded values, width x height), for the window to blit.
    GLuint display_texture() const;

    int width() const;
    int height() const;

private:
    struct impl;
    std::unique_ptr<impl> p_;
};

}  // namespace emcv::demo
