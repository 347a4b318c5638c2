// SPDX-License-Identifier: MIT
// The frame's pass list follows the scene: shadow passes only for lights that cast, SSS passes only when an
// SSS object can be visible and the method scatters; and the renderer records exactly that list.
#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "../gpu/gl_test_support.hpp"
#include "gl/debug.hpp"
#include "render/adaptive/history.hpp"
#include "render/renderer.hpp"
#include "render/tunables.hpp"
#include "render_test_support.hpp"
#include "scene/load.hpp"

using namespace emcv::demo;

namespace {

bool has_pass(const std::vector<std::string>& passes, const std::string& prefix) {
    return std::any_of(passes.begin(), passes.end(), [&](const std::string& p) { return p.rfind(prefix, 0) == 0; });
}

const method burley16{method::kind::burley, 16};

}  // namespace

TEST_CASE("pass lists of scenes built in code") {
    const scene sphere = emcv::test::sphere_on_floor();
    CHECK(pass_list(sphere, burley16, 0, 64, 48, resolve_mode::none) ==
          std::vector<std::string>{"gbuffer", "shadow:key", "shadow:spot", "lighting", "sss-burley", "composite"});
    CHECK(pass_list(sphere, method{method::kind::separable, 17}, 0, 64, 48, resolve_mode::none) ==
          std::vector<std::string>{"gbuffer", "shadow:key", "shadow:spot", "lighting", "sss-separable-h",
                                   "sss-separable-v", "composite"});
    // The adaptive methods under a quality target: burley's passes, their own sss-burley planning N over its
    // tile, sampling and updating the history in one dispatch. A budget needs the frame's variances before any
    // N: one pass more than burley's, the samples pass (which also solves the frame's scale) before it.
    CHECK(pass_list(sphere, method{method::kind::cv, 0}, 0, 64, 48, resolve_mode::none) ==
          pass_list(sphere, burley16, 0, 64, 48, resolve_mode::none));
    CHECK(pass_list(sphere, method{method::kind::cv, 0}, 0, 64, 48, resolve_mode::none, sampling_mode{true, 8.0}) ==
          std::vector<std::string>{"gbuffer", "shadow:key", "shadow:spot", "lighting", "sss-adaptive-samples",
                                   "sss-burley", "composite"});
    // diffuse never scatters.
    CHECK(pass_list(sphere, method{method::kind::diffuse, 0}, 0, 64, 48, resolve_mode::none) ==
          std::vector<std::string>{"gbuffer", "shadow:key", "shadow:spot", "lighting", "composite"});
    // Nothing scatters, nothing casts: neither an SSS nor a shadow pass.
    CHECK(pass_list(emcv::test::no_sss(), burley16, 0, 64, 48, resolve_mode::none) ==
          std::vector<std::string>{"gbuffer", "lighting", "composite"});
    // An SSS material whose only object lies outside the view frustum: no SSS pass.
    CHECK_FALSE(has_pass(pass_list(emcv::test::sss_outside_view(), burley16, 0, 64, 48, resolve_mode::none), "sss-"));
    // A point light marked casts_shadow gets no shadow pass (point lights do not cast in this renderer).
    scene point = emcv::test::sphere_on_floor();
    point.lights[1].type = light::kind::point;
    CHECK_FALSE(has_pass(pass_list(point, burley16, 0, 64, 48, resolve_mode::none), "shadow:spot"));
}

namespace {

/// light-off's camera held at frames 0-9, moving from frame 10 to frame 14, held again from frame 14 on.
scene still_move_still() {
    scene s = load_scene_argument("light-off");
    const glm::vec3 target = s.view.target;
    s.view.keys = {{0, s.view.position, target}, {10, s.view.position, target},
                   {14, s.view.position + glm::vec3(0.3f, 0.0f, 0.0f), target}};
    return s;
}

/// Per frame from 0: (records sss-adaptive-samples, its sss-burley plans the next frame), as one planner plans
/// the frames in order.
std::vector<std::pair<bool, bool>> plan_sequence(const scene& s, const method& m, const sampling_mode& sampling,
                                                 int frames, bool jitter = false) {
    frame_planner planner(s, m, 64, 48, resolve_mode::taa, sampling, jitter);
    std::vector<std::pair<bool, bool>> out;
    for (int frame = 0; frame < frames; ++frame) {
        bool samples = false, plans = false;
        for (const planned_pass& p : planner.plan(frame)) {
            samples = samples || p.id == pass_id::sss_adaptive_samples;
            if (p.id == pass_id::sss_burley) plans = p.burley == burley_variant::plans_next;
            CHECK((p.burley != burley_variant::updates && p.id != pass_id::sss_burley) == false);
        }
        CHECK(planner.planned_by_previous() == (is_adaptive(m) && sampling.budget && !samples && planner.scatters()));
        out.emplace_back(samples, plans);
    }
    return out;
}

}  // namespace

TEST_CASE("a budget's burley pass plans the next frame where the camera holds, and that frame records no samples pass") {
    const scene s = still_move_still();
    const method cv{method::kind::cv, 0};
    const sampling_mode budget{true, 8.0, true};
    const std::vector<std::pair<bool, bool>> seq = plan_sequence(s, cv, budget, 20);
    for (int frame = 0; frame < 20; ++frame) {
        INFO("frame " << frame);
        const bool moved_in = frame >= 11 && frame <= 14;  // its camera differs from frame - 1's
        const bool moves_next = frame >= 10 && frame <= 13;  // frame + 1's camera differs from its own
        CHECK(seq[std::size_t(frame)].first == (frame == 0 || moved_in));
        CHECK(seq[std::size_t(frame)].second == !moves_next);
    }
    // Every adaptive method alike; spvg's passes are cv's.
    CHECK(plan_sequence(s, method{method::kind::spvg, 0}, budget, 20) == seq);
    CHECK(plan_sequence(s, method{method::kind::cv_notex, 0}, budget, 20) == seq);
    // Never with EMCV_HISTORY_PLAN_AHEAD=0, under a quality target (no samples pass to spare), under jitter (the
    // camera moves every frame), for burley-N (no history).
    for (const auto& [samples, plans] : plan_sequence(s, cv, sampling_mode{true, 8.0, false}, 20)) {
        CHECK(samples);
        CHECK_FALSE(plans);
    }
    for (const auto& [samples, plans] : plan_sequence(s, cv, sampling_mode{false, 1e-4, false}, 20)) {
        CHECK_FALSE(samples);
        CHECK_FALSE(plans);
    }
    for (const auto& [samples, plans] : plan_sequence(s, cv, budget, 20, true)) {
        CHECK(samples);
        CHECK_FALSE(plans);
    }
    for (const auto& [samples, plans] : plan_sequence(s, burley16, budget, 20)) CHECK_FALSE((samples || plans));
    // A camera that moves every frame: every frame plans itself.
    for (const auto& [samples, plans] : plan_sequence(load_scene_argument("moving"), cv, budget, 20)) {
        CHECK(samples);
        CHECK_FALSE(plans);
    }
    // Frames out of order: only frame + 1 is planned by frame.
    frame_planner planner(s, cv, 64, 48, resolve_mode::taa, budget);
    planner.plan(0);
    planner.plan(5);
    CHECK_FALSE(planner.planned_by_previous());
    planner.plan(6);
    CHECK(planner.planned_by_previous());
}

TEST_CASE("learning_updates: enough updates for a pixel gone dark to fall from B samples to N_MIN, at least 1 / eta") {
    // 2 ln(8) / -ln(0.8) = 4.1589 / 0.22314 = 18.64 -> 19; B = 2.5: 2 ln(2.5) / 0.22314 = 8.21 -> 9;
    // B = 1 (nothing to release): the memory 1 / 0.2 = 5; eta = 0.1, B = 8: 4.1589 / 0.10536 = 39.47 -> 40;
    // N_MIN = 2, B = 8: 2 ln(4) / 0.22314 = 12.42 -> 13.
    CHECK(learning_updates(0.2, 8.0, 1.0) == 19);
    CHECK(learning_updates(0.2, 2.5, 1.0) == 9);
    CHECK(learning_updates(0.2, 1.0, 1.0) == 5);
    CHECK(learning_updates(0.1, 8.0, 1.0) == 40);
    CHECK(learning_updates(0.2, 8.0, 2.0) == 13);
    // The renderer's sampling mode takes the slower weight of the two.
    define_list defines{{"EMCV_HISTORY_SPP_BUDGET", "8"}, {"EMCV_HISTORY_ETA_MOVING", "0.1"}};
    CHECK(sampling_mode_of(defines).learning_updates == 40);
    defines = {{"EMCV_HISTORY_SPP_BUDGET", "8"}, {"EMCV_HISTORY_ETA_EMCM", "0.1"}};
    CHECK(sampling_mode_of(defines).learning_updates == 40);
}

namespace {

/// Per frame from 0: whether the burley pass reuses the last update's plan, as one planner plans the frames in
/// order; `light_scale` from frame `scaled_from` on.
std::vector<bool> reuse_sequence(const scene& s, const sampling_mode& sampling, int frames, int scaled_from = -1,
                                 std::vector<float> light_scale = {}) {
    frame_planner planner(s, method{method::kind::cv, 0}, 64, 48, resolve_mode::taa, sampling);
    std::vector<bool> out;
    for (int frame = 0; frame < frames; ++frame) {
        bool reuses = false, samples = false;
        for (const planned_pass& p : planner.plan(frame, frame >= scaled_from ? light_scale : std::vector<float>{})) {
            samples = samples || p.id == pass_id::sss_adaptive_samples;
            if (p.id != pass_id::sss_burley) continue;
            reuses = p.burley == burley_variant::reuses_plan;
        }
        CHECK(planner.reuses_plan() == reuses);
        if (reuses) CHECK_FALSE(samples);  // only a frame planned by the previous one reuses
        out.push_back(reuses);
    }
    return out;
}

}  // namespace

TEST_CASE("a budget updates the history on one frame in M where view and lights hold, after the learning updates") {
    // light-off: the camera holds at frames 0-9 and from 14 on (moving in at 11-14), the key light goes off at 30.
    const scene s = still_move_still();
    sampling_mode budget{true, 8.0, true, 4, 19};
    const std::vector<bool> seq = reuse_sequence(s, budget, 80);
    // Every change restarts the count of updates: frame 0, the camera at 11-14 (frame 14 the last one moved in),
    // the light at 30. 19 updates from frame 30 are frames 30-48; from 49 on three frames of four reuse the plan.
    for (int frame = 0; frame < 80; ++frame) {
        INFO("frame " << frame);
        CHECK(seq[std::size_t(frame)] == (frame >= 49 && (frame - 49) % 4 != 3));
    }
    // The window's toggles change a light too: scaled from frame 60 on, the count restarts there.
    const std::vector<bool> toggled = reuse_sequence(s, budget, 100, 60, {0.5f, 0.5f, 0.5f, 0.5f});
    for (int frame = 0; frame < 100; ++frame) {
        INFO("frame " << frame);
        CHECK(toggled[std::size_t(frame)] == ((frame >= 49 && frame < 60 && (frame - 49) % 4 != 3) ||
                                              (frame >= 79 && (frame - 79) % 4 != 3)));
    }
    // A shorter learning and another period, one frame in 2: the still stretches before the switch learn too.
    // Frames 0-4 update, 5-9 alternate; 10 updates (the frame after a reuse); 11-14 move in; 14-18 update, 19-29
    // alternate; the switch at 30, and from 35 on.
    const std::vector<bool> short_seq = reuse_sequence(s, sampling_mode{true, 8.0, true, 2, 5}, 50);
    for (int frame = 0; frame < 50; ++frame) {
        INFO("frame " << frame);
        const bool alternates = (frame >= 5 && frame <= 9) || (frame >= 19 && frame <= 29);
        CHECK(short_seq[std::size_t(frame)] == ((alternates && frame % 2 == 1) || (frame >= 35 && (frame - 35) % 2 == 0)));
    }
    // Never with M = 1, without planning ahead, under a quality target, or where the camera moves every frame.
    for (const bool reuses : reuse_sequence(s, sampling_mode{true, 8.0, true, 1, 19}, 80)) CHECK_FALSE(reuses);
    for (const bool reuses : reuse_sequence(s, sampling_mode{true, 8.0, false, 4, 19}, 80)) CHECK_FALSE(reuses);
    for (const bool reuses : reuse_sequence(s, sampling_mode{false, 1e-4, false, 4, 19}, 80)) CHECK_FALSE(reuses);
    for (const bool reuses : reuse_sequence(load_scene_argument("moving"), budget, 60)) CHECK_FALSE(reuses);  // moves to 59
}

TEST_CASE("a burley pass that plans the next frame leaves every image, count and alpha as the samples pass would, bit for bit", "[image-files]") {
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    // Still, moving, still again; the key light switches off at frame 30 (light-off), under the planned frames.
    const scene s = still_move_still();
    // cv's planning pass takes the histories it stored from its registers (emcv_adaptive_as_stored), the others
    // load them back; K = 2 plans blocks.
    for (const method& m : {method{method::kind::cv, 0}, method{method::kind::spvg, 0}, method{method::kind::cv_notex, 0}})
    for (const int block : {1, 2}) {
        INFO(m.name() << ", K = " << block);
        render_options planned;
        planned.width = 48;
        planned.height = 32;
        add_define(planned.defines, "EMCV_HISTORY_SPP_BUDGET=4");
        add_define(planned.defines, "EMCV_HISTORY_BLOCK=" + std::to_string(block));
        add_define(planned.defines, "EMCV_HISTORY_UPDATE_PERIOD=1");  // every frame updates (reuse: the test below)
        render_options unplanned = planned;
        add_define(unplanned.defines, "EMCV_HISTORY_PLAN_AHEAD=0");
        renderer a(s, m, planned), b(s, m, unplanned);
        frame_planner listing(s, m, planned.width, planned.height, planned.resolve, sampling_mode_of(planned.defines));
        int planned_frames = 0;
        for (int frame = 0; frame < 34; ++frame) {
            INFO("frame " << frame);
            std::vector<std::string> recorded;
            for (const pass_time& p : a.render(frame).times.passes) recorded.emplace_back(p.name);
            b.render(frame);
            // the renderer records the list its planner prints, the samples pass only where no frame planned it
            std::vector<std::string> listed;
            for (const planned_pass& p : listing.plan(frame)) listed.push_back(pass_name(s, p));
            CHECK(recorded == listed);
            if (listing.planned_by_previous()) ++planned_frames;
            CHECK(has_pass(recorded, "sss-adaptive-samples") == !listing.planned_by_previous());
            CHECK(a.sample_counts().pixels == b.sample_counts().pixels);
            CHECK(a.linear().pixels == b.linear().pixels);
            CHECK(a.shown().pixels == b.shown().pixels);
            CHECK(a.cv_alpha().pixels == b.cv_alpha().pixels);
        }
        CHECK(planned_frames == 34 - 5);  // all but frame 0 and the moving frames 11-14
    }
    CHECK(messenger.error_count() == 0);
}

namespace {

/// The history as read back, flattened (a then b per texel): equal bit for bit where the floats are equal.
std::vector<float> history_values(renderer& r) {
    std::vector<float> out;
    for (const adaptive::texel& t : r.adaptive_history()->read())
        out.insert(out.end(), {t.a.x, t.a.y, t.a.z, t.a.w, t.b.x, t.b.y});
    return out;
}

}  // namespace

TEST_CASE("a frame that reuses the plan samples as the updating frame would and leaves the history and the budget as they were", "[image-files]") {
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    const scene s = still_move_still();  // still at frames 0-9
    for (const method& m : {method{method::kind::cv, 0}, method{method::kind::spvg, 0}, method{method::kind::cv_notex, 0}}) {
        INFO(m.name());
        render_options every;
        every.width = 48;
        every.height = 32;
        // eta 0.5 and B = 4: 4 learning updates (2 ln 4 / ln 2 = 4), frames 0-3; then frames 4-6 reuse, 7 updates.
        add_define(every.defines, "EMCV_HISTORY_SPP_BUDGET=4");
        add_define(every.defines, "EMCV_HISTORY_ETA_EMCM=0.5");
        add_define(every.defines, "EMCV_HISTORY_ETA_MOVING=0.5");
        render_options amortized = every;
        add_define(amortized.defines, "EMCV_HISTORY_UPDATE_PERIOD=4");
        REQUIRE(sampling_mode_of(amortized.defines).learning_updates == 4);
        renderer a(s, m, amortized), b(s, m, every);
        frame_planner listing(s, m, amortized.width, amortized.height, amortized.resolve, sampling_mode_of(amortized.defines));
        std::vector<float> before = history_values(a);
        emcv::port::EmcvBudgetBlock last_budget = a.adaptive_history()->read_budget();
        for (int frame = 0; frame < 10; ++frame) {
            INFO("frame " << frame);
            a.render(frame);
            b.render(frame);
            listing.plan(frame);
            CHECK(listing.reuses_plan() == (frame >= 4 && frame != 7));
            const std::vector<float> after = history_values(a);
            const emcv::port::EmcvBudgetBlock budget = a.adaptive_history()->read_budget();
            if (listing.reuses_plan()) {
                // no update, no planning, no solve: the history and lambda as the last update left them
                CHECK(after == before);
                CHECK(budget.solves == last_budget.solves);
                CHECK(budget.lambda == last_budget.lambda);
            } else {
                CHECK(after != before);
                CHECK(budget.solves > last_budget.solves);
            }
            before = after;
            last_budget = budget;
            // Up to the first frame that reuses the plan, both sample with the same plan: the same counts and
            // image, bit for bit (the frame before planned it either way).
            if (frame <= 4) {
                CHECK(a.sample_counts().pixels == b.sample_counts().pixels);
                CHECK(a.linear().pixels == b.linear().pixels);
            }
        }
    }
    CHECK(messenger.error_count() == 0);
}

TEST_CASE("the temporal resolve: one pass after the composite, for every method but the reference, never under none") {
    const scene sphere = emcv::test::sphere_on_floor();
    for (const method& m : all_methods()) {
        INFO(m.name());
        const std::vector<std::string> raw = pass_list(sphere, m, 0, 64, 48, resolve_mode::none);
        const std::vector<std::string> resolved = pass_list(sphere, m, 0, 64, 48, resolve_mode::taa);
        CHECK_FALSE(has_pass(raw, "resolve"));
        if (m.type == method::kind::reference) {
            CHECK(resolved == raw);  // the converged image is compared as it is
        } else {
            std::vector<std::string> expected = raw;
            expected.push_back("resolve");
            CHECK(resolved == expected);
        }
    }
    // A scene without SSS resolves too: what is shown does not depend on whether it scatters.
    CHECK(pass_list(emcv::test::no_sss(), burley16, 0, 64, 48, resolve_mode::taa) ==
          std::vector<std::string>{"gbuffer", "lighting", "composite", "resolve"});
}

TEST_CASE("a light whose curve is 0 at a frame records no shadow pass that frame") {
    // light-off's key light steps from 2 to 0 at frame 30 (tests/scene checks the curve): shadow:key on
    // frames 0..29 only, the spot fill (casts_shadow false) never.
    const scene light_off = load_scene_argument("light-off");
    for (int frame = 0; frame < light_off.frames; ++frame) {
        INFO("frame " << frame);
        const std::vector<std::string> passes = pass_list(light_off, burley16, frame, 128, 96, resolve_mode::none);
        CHECK(has_pass(passes, "shadow:key") == (frame < 30));
        CHECK_FALSE(has_pass(passes, "shadow:fill"));
    }
    // A flicker curve on a shadow caster: the pass exists only during bursts.
    scene burst = emcv::test::sphere_on_floor();
    curve& flash = burst.lights[0].intensity;
    flash.type = curve::kind::flicker;
    flash.value = 0.0f;
    flash.peak = 5.0f;
    flash.bursts = {4};
    flash.burst_length = 2;
    CHECK_FALSE(has_pass(pass_list(burst, burley16, 3, 64, 48, resolve_mode::none), "shadow:key"));
    CHECK(has_pass(pass_list(burst, burley16, 4, 64, 48, resolve_mode::none), "shadow:key"));
    CHECK(has_pass(pass_list(burst, burley16, 5, 64, 48, resolve_mode::none), "shadow:key"));
    CHECK_FALSE(has_pass(pass_list(burst, burley16, 6, 64, 48, resolve_mode::none), "shadow:key"));
    CHECK(has_pass(pass_list(burst, burley16, 6, 64, 48, resolve_mode::none), "shadow:spot"));
}

TEST_CASE("pass list of each built-in scene", "[image-files]") {
    const std::vector<std::string> names = builtin_scene_names();
    REQUIRE(std::find(names.begin(), names.end(), "no-sss") != names.end());
    for (const std::string& name : names) {
        INFO("scene " << name);
        const scene s = load_scene_argument(name);
        const std::vector<std::string> passes = pass_list(s, burley16, 0, 128, 96, resolve_mode::none);
        CHECK(passes.front() == "gbuffer");
        CHECK(passes.back() == "composite");
        const bool casters = std::any_of(s.lights.begin(), s.lights.end(), [](const light& l) {
            return l.casts_shadow && l.type != light::kind::point;
        });
        CHECK(has_pass(passes, "shadow:") == casters);
        CHECK(has_pass(passes, "sss-") == s.has_sss_material());  // every built-in SSS object is in view
        if (name == "no-sss") {
            CHECK(passes == std::vector<std::string>{"gbuffer", "lighting", "composite"});
        }
    }
}

TEST_CASE("the renderer records exactly the pass list", "[image-files]") {
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    std::vector<scene> scenes{emcv::test::sphere_on_floor(), emcv::test::no_sss(), emcv::test::sss_outside_view()};
    for (const std::string& name : builtin_scene_names()) scenes.push_back(load_scene_argument(name));
    for (const scene& s : scenes) {
        for (const method& m : all_methods()) {
            INFO("scene " << s.name << ", method " << m.name());
            render_options options;
            options.width = 32;
            options.height = 24;
            renderer r(s, m, options);
            const frame_stats& stats = r.render(0);
            std::vector<std::string> recorded;
            for (const pass_time& p : stats.times.passes) recorded.emplace_back(p.name);
            CHECK(recorded == pass_list(s, m, 0, 32, 24, resolve_mode::none));
            {  // with the temporal resolve, its list: the resolve pass after the composite (not the reference's)
                render_options taa = options;
                taa.resolve = resolve_mode::taa;
                renderer rt(s, m, taa);
                std::vector<std::string> recorded_taa;
                for (const pass_time& p : rt.render(0).times.passes) recorded_taa.emplace_back(p.name);
                CHECK(recorded_taa == pass_list(s, m, 0, 32, 24, resolve_mode::taa));
                CHECK(has_pass(recorded_taa, "resolve") == (m.type != method::kind::reference));
            }
            if (!has_pass(recorded, "sss-")) {
                CHECK(stats.times.sss_ms == 0.0);
                CHECK(stats.sss_pixels == 0);
            }
            {  // GPU timestamps time the same passes as the wall clock, frames later (take_times waits at the end)
                render_options gpu = options;
                gpu.timing_mode = timing::gpu;
                renderer rg(s, m, gpu), rw(s, m, options);
                std::vector<std::vector<std::string>> wall_lists;
                for (int frame = 0; frame < 3; ++frame) {
                    rg.render(frame);
                    wall_lists.emplace_back();
                    for (const pass_time& p : rw.render(frame).times.passes) wall_lists.back().emplace_back(p.name);
                }
                const std::vector<frame_times> times = rg.take_times(true);
                REQUIRE(times.size() == 3);
                for (int frame = 0; frame < 3; ++frame) {
                    const frame_times& t = times[static_cast<std::size_t>(frame)];
                    CHECK(t.frame == frame);
                    std::vector<std::string> timed;
                    double sum = 0.0;
                    for (const pass_time& p : t.passes) timed.emplace_back(p.name), sum += p.ms;
                    CHECK(timed == wall_lists[static_cast<std::size_t>(frame)]);
                    CHECK(t.frame_ms == sum);
                }
                CHECK(rg.take_times(true).empty());
            }
            if (is_adaptive(m)) {  // budget mode records its samples pass, and exactly the list printed for it
                render_options budget = options;
                add_define(budget.defines, "EMCV_HISTORY_SPP_BUDGET=4");
                renderer rb(s, m, budget);
                std::vector<std::string> recorded_budget;
                for (const pass_time& p : rb.render(0).times.passes) recorded_budget.emplace_back(p.name);
                CHECK(recorded_budget ==
                      pass_list(s, m, 0, 32, 24, resolve_mode::none, sampling_mode_of(budget.defines)));
                // wherever it scatters, a budget plans the frame in a pass of its own
                CHECK(has_pass(recorded_budget, "sss-adaptive-samples") == has_pass(recorded_budget, "sss-burley"));
            }
        }
    }
    CHECK(messenger.error_count() == 0);
}

TEST_CASE("the renderer skips a dark light's shadow pass on the frames it is dark") {
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    const scene light_off = load_scene_argument("light-off");
    render_options options;
    options.width = 32;
    options.height = 24;
    renderer r(light_off, burley16, options);
    for (int frame : {0, 29, 30, 31, 59}) {
        INFO("frame " << frame);
        const frame_stats& stats = r.render(frame);
        std::vector<std::string> recorded;
        for (const pass_time& p : stats.times.passes) recorded.emplace_back(p.name);
        CHECK(recorded == pass_list(light_off, burley16, frame, 32, 24, resolve_mode::none));
        CHECK(has_pass(recorded, "shadow:key") == (frame < 30));
    }
    CHECK(messenger.error_count() == 0);
}

TEST_CASE("the timing flag: auto picks GPU timestamps on a hardware renderer and the wall clock on a software one") {
    CHECK(parse_timing("auto") == timing_request::automatic);
    CHECK(parse_timing("wall") == timing_request::wall);
    CHECK(parse_timing("gpu") == timing_request::gpu);
    for (const char* bad : {"", "GPU", "cpu", "gpu ", "timestamps"}) {
        INFO("'" << bad << "'");
        CHECK_FALSE(parse_timing(bad).has_value());
        CHECK_THROWS_AS(parse_timing_flag(bad), timing_error);
    }
    // GL_RENDERER strings as the drivers report them.
    const char* software[] = {"llvmpipe (LLVM 15.0.6, 256 bits)", "softpipe", "SwiftShader Device (Subzero)"};
    const char* hardware[] = {"NVIDIA H200/PCIe/SSE2", "AMD Radeon RX 7900 XTX (radeonsi, navi31, LLVM 15.0.7)",
                              "Mesa Intel(R) UHD Graphics 630 (CFL GT2)"};
    for (const char* r : software) {
        INFO(r);
        CHECK(resolve_timing(timing_request::automatic, r) == timing::wall);
        CHECK(resolve_timing(timing_request::gpu, r) == timing::gpu);  // an explicit request wins
    }
    for (const char* r : hardware) {
        INFO(r);
        CHECK(resolve_timing(timing_request::automatic, r) == timing::gpu);
        CHECK(resolve_timing(timing_request::wall, r) == timing::wall);
    }
    CHECK(std::string(timing_name(timing::gpu)) == "gpu");
    CHECK(std::string(timing_name(timing::wall)) == "wall");
}
