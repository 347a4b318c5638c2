// SPDX-License-Identifier: MIT
// The frame's pass list, derived from the scene (pass_list.hpp): only the passes the scene calls for.
#include "pass_list.hpp"

#include <algorithm>

namespace emcv::demo {

std::string_view pass_base_name(pass_id id) {
    switch (id) {
        case pass_id::gbuffer: return "gbuffer";
        case pass_id::shadow: return "shadow";
        case pass_id::lighting: return "lighting";
        case pass_id::sss_adaptive_samples: return "sss-adaptive-samples";
        case pass_id::sss_burley: return "sss-burley";
        case pass_id::sss_separable_h: return "sss-separable-h";
        case pass_id::sss_separable_v: return "sss-separable-v";
        case pass_id::composite: return "composite";
        case pass_id::resolve: return "resolve";
    }
    return "unknown";
}

bool is_sss_pass(pass_id id) { return pass_base_name(id).substr(0, 4) == "sss-"; }

std::string pass_name(const scene& s, const planned_pass& p) {
    if (p.id == pass_id::shadow) return "shadow:" + s.lights.at(p.light).name;
    return std::string(pass_base_name(p.id));
}

bool light_has_shadow_pass(const light& l) { return l.casts_shadow && l.type != light::kind::point; }

bool light_shines(const light& l, int frame) { return l.intensity.at(frame) > 0.0f; }

std::vector<std::size_t> shadow_casters(const scene& s) {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < s.lights.size(); ++i)
        if (light_has_shadow_pass(s.lights[i])) out.push_back(i);
    return out;
}

frame_planner::frame_planner(const scene& s, const method& m, int width, int height, resolve_mode resolve,
                             const sampling_mode& sampling, bool jitter)
    : s_(&s), m_(m), width_(width), height_(height), resolve_(resolve), budget_(sampling.budget),
      plan_ahead_(sampling.budget && sampling.plan_ahead),
      update_period_(plan_ahead_ ? sampling.update_period : 1), learning_updates_(sampling.learning_updates),
      jitter_(jitter && resolve == resolve_mode::taa && row_of(m).resolves()), casters_(shadow_casters(s)) {
    for (const object& o : s.objects)
        if (s.materials.at(static_cast<std::size_t>(o.material)).scatters()) sss_bounds_.push_back(object_bounds(s, o));
    passes_.reserve(casters_.size() + 8);
    inputs_.assign(6 + 3 * s.lights.size(), 0.0f);
    held_inputs_ = inputs_;
    lights_.assign(3 * s.lights.size(), 0.0f);
    previous_lights_ = lights_;
}

const std::vector<planned_pass>& frame_planner::plan(int frame, const std::vector<float>& light_scale) {
    const scene& s = *s_;
    view_ = camera_matrices(s.view, frame, width_, height_);
    if (jitter_) view_ = jittered(view_, taa_jitter(frame), width_, height_);
    const view_matrices& v = view_;
    const bool visible = m_.scatters() && std::any_of(sss_bounds_.begin(), sss_bounds_.end(), [&](const bounding_sphere& b) {
                             return sphere_in_frustum(v.view_proj, b);
                         });
    // The ground truth is the converged integral: it is rendered again only when its inputs changed (camera pose,
    // light radiance; objects do not move in this scene model), else its last result is shown again.
    previous_lights_.swap(lights_);
    for (std::size_t i = 0; i < s.lights.size(); ++i) {
        const float scale = i < light_scale.size() ? light_scale[i] : 1.0f;
        const glm::vec3 e = s.lights[i].color * s.lights[i].intensity.at(frame) * scale;
        lights_[3 * i] = e.x; lights_[3 * i + 1] = e.y; lights_[3 * i + 2] = e.z;
    }
    reused_ = false;
    if (row_of(m_).holds_result() && visible) {
        inputs_[0] = v.position.x; inputs_[1] = v.position.y; inputs_[2] = v.position.z;
        inputs_[3] = v.target.x; inputs_[4] = v.target.y; inputs_[5] = v.target.z;
        std::copy(lights_.begin(), lights_.end(), inputs_.begin() + 6);
        reused_ = held_ && inputs_ == held_inputs_;
        if (!reused_) {
            held_inputs_ = inputs_;
            held_ = true;
        }
    }
    scatters_ = visible && !reused_;
    planned_by_previous_ = false;
    reuses_plan_ = false;

    passes_.clear();
    passes_.push_back({pass_id::gbuffer, 0, 0});
    for (std::size_t layer = 0; layer < casters_.size(); ++layer)
        if (light_shines(s.lights[casters_[layer]], frame)) passes_.push_back({pass_id::shadow, casters_[layer], layer});
    passes_.push_back({pass_id::lighting, 0, 0});
    if (scatters_) {
        switch (row_of(m_).passes()) {
            case sss_passes::none: break;
            case sss_passes::burley: passes_.push_back({pass_id::sss_burley, 0, 0}); break;
            case sss_passes::separable:
                passes_.push_back({pass_id::sss_separable_h, 0, 0});
                passes_.push_back({pass_id::sss_separable_v, 0, 0});
                break;
            case sss_passes::adaptive: {
                // The method's own burley program, which also updates the history (and under a quality target
                // first plans N over its tile); a budget records one pass more before it: the samples pass,
                // after which a one-workgroup dispatch solves the frame's scale from every pixel's variance; unless the last
                // frame's burley pass planned this frame (same view), which this frame's does for the next
                // frame when that one shows this view again.
                planned_by_previous_ = plan_ahead_ && planned_frame_ == frame;
                if (budget_ && !planned_by_previous_) passes_.push_back({pass_id::sss_adaptive_samples, 0, 0});
                const bool same_next = plan_ahead_ && !jitter_ && same_camera(camera_matrices(s.view, frame + 1, width_, height_), v);
                // Updating one frame in M: a still view (planned by the previous frame) under still lights, whose
                // history has learnt since the last change, reuses the last update's plan on M - 1 frames of M.
                if (!planned_by_previous_ || lights_ != previous_lights_) updates_since_change_ = 0;
                reuses_plan_ = planned_by_previous_ && updates_since_change_ >= learning_updates_ &&
                               reuses_since_update_ + 1 < update_period_;
                // A frame that reuses the plan leaves it valid for the next frame of the same view.
                passes_.push_back({pass_id::sss_burley, 0, 0,
                                   reuses_plan_ ? burley_variant::reuses_plan
                                   : same_next  ? burley_variant::plans_next
                                                : burley_variant::updates});
                if (reuses_plan_) {
                    ++reuses_since_update_;
                } else {
                    reuses_since_update_ = 0;
                    ++updates_since_change_;
                }
                planned_frame_ = same_next ? frame + 1 : -1;
                break;
            }
        }
    }
    if (!scatters_) planned_frame_ = -1;  // no burley pass planned the next frame, and no history was updated here
    passes_.push_back({pass_id::composite, 0, 0});
    // The reference is the converged image an engine's resolve would converge to: it is compared raw.
    if (resolve_ == resolve_mode::taa && row_of(m_).resolves()) passes_.push_back({pass_id::resolve, 0, 0});
    return passes_;
}

std::vector<std::string> pass_list(const scene& s, const method& m, int frame, int width, int height,
                                   resolve_mode resolve, const sampling_mode& sampling) {
    frame_planner planner(s, m, width, height, resolve, sampling);
    std::vector<std::string> names;
    for (const planned_pass& p : planner.plan(frame)) names.push_back(pass_name(s, p));
    return names;
}

}  // namespace emcv::demo
