// SPDX-License-Identifier: MIT
// emcv::demo pass list: the passes a frame records, derived from the scene and the method (docs/frame.md).
// The renderer walks exactly the list frame_planner::plan returns, and `--print-passes` prints the same list:
// what is printed and what runs come from this one place.
//   gbuffer          linear view depth R32F, normal, albedo, material id, motion (previous frame's camera)
//   shadow:<light>   one per light with casts_shadow that shines this frame (point lights never cast here)
//   lighting         diffuse irradiance without albedo (RGBA16F) kept apart from specular GGX (RGBA16F); on a
//                    frame with SSS passes also the 8x8 tiles holding an SSS pixel, appended on the GPU, and
//                    their indirect dispatch arguments (render/tiles.h): no SSS pass runs over the full screen
//   the method's SSS passes (method.hpp, sss_passes), over the SSS tiles only (indirect dispatch)
//   composite        post-scatter albedo * scattered (or unscattered) diffuse + specular, tonemap, sRGB
//   resolve          --resolve taa: the temporal resolve of the composite's image (every method but the
//                    reference, whose image is converged); not recorded under --resolve none
// The SSS passes (and the tile list) are not recorded for a method that does not scatter, for a scene with no SSS
// material, when every SSS object lies outside the view frustum, or when the reference's inputs are those of
// the result it already holds (it is shown again).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "method.hpp"
#include "resolve.hpp"
#include "scene/scene.hpp"
#include "tunables.hpp"
#include "view.hpp"

namespace emcv::demo {

enum class pass_id {
    gbuffer,
    shadow,
    lighting,  ///< also lists the SSS tiles on frames with SSS passes
    sss_adaptive_samples,  ///< budget mode only: each pixel's variance from the reprojected history, and the
                           ///< scale of N = clamp(lambda sigma) solved by a one-workgroup dispatch after it
    sss_burley,            ///< adaptive methods: their own program, which also pushes (f, G) into the history
                           ///< (and under a quality target first plans N itself)
    sss_separable_h,
    sss_separable_v,
    composite,
    resolve,  ///< the temporal resolve (resolve.hpp), after the composite
};
inline constexpr std::size_t pass_id_count = 9;

/// "gbuffer", "shadow", "lighting", "sss-adaptive-samples", "sss-burley", ...
std::string_view pass_base_name(pass_id id);
/// The passes counted in frame_stats::sss_ms.
bool is_sss_pass(pass_id id);

/// An adaptive method's burley program on a frame (planned_pass::burley; adaptive::history::use_burley).
enum class burley_variant {
    updates,      ///< samples, then pushes (f, G) into the history
    /// budget mode, the next frame showing this frame's view (frame_planner::plan): also plans that frame's counts
    /// (EMCV_ADAPTIVE_PLAN_NEXT), so that frame records no sss-adaptive-samples
    plans_next,
    /// budget mode, a frame between two updates of a still view under still lights (sampling_mode::update_period):
    /// samples with the counts the last update planned, neither updates the history nor plans
    /// (EMCV_ADAPTIVE_REUSE_PLAN; no samples pass either)
    reuses_plan,
};

struct planned_pass {
    pass_id id = pass_id::gbuffer;
    std::size_t light = 0;  ///< shadow: the light's index in the scene
    std::size_t layer = 0;  ///< shadow: its layer in the shadow-map array
    burley_variant burley = burley_variant::updates;  ///< sss_burley of an adaptive method: its program
    bool operator==(const planned_pass& o) const {
        return id == o.id && light == o.light && layer == o.layer && burley == o.burley;
    }
};

/// "shadow:<light name>" for a shadow pass, the base name otherwise.
std::string pass_name(const scene& s, const planned_pass& p);

/// The lights with a shadow-map layer, in layer order.
std::vector<std::size_t> shadow_casters(const scene& s);

/// Plans each frame's passes in order. Frames are planned in increasing order: the reference's reuse compares
/// this frame's SSS inputs (camera pose, light radiance) with those of the result it holds. plan() allocates
/// nothing after the first call.
class frame_planner {
public:
    /// `resolve`: whether a frame ends with the temporal resolve (not for the reference).
    /// `sampling`: the adaptive methods' mode (sampling_mode_of the render options' defines). A budget needs
    /// every pixel's variance before any pixel's N, so it records the adaptive-samples pass (which also solves
    /// the frame's scale) before the method's burley program; a quality target needs only the pixel's tile,
    /// and the burley program plans N itself (no pass more than burley-N's).
    /// Under a budget with `sampling.plan_ahead`, a frame whose next frame (frame + 1) shows the same camera
    /// (view and projection bit for bit, so the same G-buffer: objects do not move in the scene model) plans that
    /// frame's counts in its burley pass (burley_variant::plans_next), and that frame, planned next, records no
    /// samples pass: the data of a still view allow the fusion. Any other frame records it.
    /// With `sampling.update_period` M > 1, a frame planned by the previous one whose lights (each one's radiance
    /// times `light_scale`) are those of the previous frame reuses that plan (burley_variant::reuses_plan) once the
    /// history has taken `sampling.learning_updates` updates since the last change of view or lights, unless M - 1
    /// frames have reused it since the last update: the history is updated on one frame in M.
    /// `jitter`: the camera moves by taa_jitter(frame) under resolve taa (render_options::jitter; never the
    /// reference's).
    frame_planner(const scene& s, const method& m, int width, int height, resolve_mode resolve,
                  const sampling_mode& sampling, bool jitter = false);

    /// The passes of `frame`; `light_scale` multiplies each light's intensity (the window's toggles), empty
    /// for 1 everywhere.
    const std::vector<planned_pass>& plan(int frame, const std::vector<float>& light_scale = {});
    /// Whether the last planned frame shows the reference's held result again.
    bool reuses_result() const { return reused_; }
    /// Whether the last planned frame records SSS passes.
    bool scatters() const { return scatters_; }
    /// Whether the last planned frame shows scattered light (its SSS passes run, or the reference's held result).
    bool shows_sss() const { return scatters_ || reused_; }
    /// Whether the last planned frame's resolve narrows its box to the noise of a Monte Carlo SSS pass
    /// (resolve.comp.glsl: a resolve without jitter after the burley pass): only then does the burley pass keep
    /// and store its noise (EMCV_RENDER_FLAG_SSS_NOISE).
    bool resolves_sss_noise() const {
        return scatters_ && samples_randomly(m_) && resolve_ == resolve_mode::taa && !jitter_ &&
               row_of(m_).resolves();
    }
    /// Whether the last planned frame's counts were planned by the frame before it (its burley pass was
    /// burley_variant::plans_next, or reused a plan of the same view): it records no samples pass, and its history is updated where that frame left it (in place,
    /// adaptive::history::begin_frame).
    bool planned_by_previous() const { return planned_by_previous_; }
    /// Whether the last planned frame's burley pass reuses the last update's plan (burley_variant::reuses_plan).
    bool reuses_plan() const { return reuses_plan_; }
    /// The camera of the last planned frame (the renderer uploads it).
    const view_matrices& view() const { return view_; }
    /// Forget the held result (method switch).
    void reset() { held_ = false; }

private:
    const scene* s_;
    method m_;
    int width_, height_;
    resolve_mode resolve_;
    bool budget_;
    bool plan_ahead_;
    int update_period_;    ///< sampling_mode::update_period
    int learning_updates_;  ///< sampling_mode::learning_updates
    bool jitter_;
    std::vector<bounding_sphere> sss_bounds_;
    std::vector<std::size_t> casters_;
    std::vector<planned_pass> passes_;
    std::vector<float> inputs_, held_inputs_;
    std::vector<float> lights_, previous_lights_;  ///< each light's radiance (times its scale) this and last frame
    view_matrices view_;
    bool held_ = false, reused_ = false, scatters_ = false;
    int planned_frame_ = -1;  ///< the frame the last planned frame's burley pass plans (-1: none)
    bool planned_by_previous_ = false;
    bool reuses_plan_ = false;
    int updates_since_change_ = 0;  ///< history updates since the last change of view or lights
    int reuses_since_update_ = 0;   ///< frames that reused the plan since the last update
};

/// The names of frame_planner's list for one frame, planned from scratch (no held reference result): what
/// `--print-passes` prints for frame 0 and the tests compare with. `sampling`: the adaptive methods' mode
/// (default: the quality target, the renderer's default).
std::vector<std::string> pass_list(const scene& s, const method& m, int frame, int width, int height,
                                   resolve_mode resolve, const sampling_mode& sampling = {});

}  // namespace emcv::demo
