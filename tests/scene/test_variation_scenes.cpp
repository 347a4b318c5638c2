// SPDX-License-Identifier: MIT
// The variation scenes (demo/scenes/variations/): light-off with one thing changed each. They exist to measure
// methods on events they were not tuned on, so the test pins what each promises (the key light's curve, the
// camera) and that everything else is light-off's, rather than anything about how a method fares on them.
#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "scene/load.hpp"
#include "scene_test_support.hpp"

using namespace emcv::demo;
using emcv::test::source_dir;

namespace {

struct variation {
    std::string name;
    int frames;
    bool camera_moves;
    std::vector<std::pair<int, float>> key;  ///< (frame, the key light's intensity there)
};

/// The key light's intensity at each frame from a list of (first frame, value), held until the next entry.
std::vector<std::pair<int, float>> held(int frames, std::vector<std::pair<int, float>> changes) {
    std::vector<std::pair<int, float>> out;
    std::size_t next = 0;
    float v = changes.front().second;
    for (int f = 0; f < frames; ++f) {
        while (next < changes.size() && changes[next].first <= f) v = changes[next++].second;
        out.emplace_back(f, v);
    }
    return out;
}

/// Every frame of each scene, so that an event one frame early or late, or a missing frame of the fade, fails.
std::vector<variation> variations() {
    std::vector<std::pair<int, float>> fade;
    for (int f = 0; f < 60; ++f)
        fade.emplace_back(f, f <= 20 ? 1.5f : f >= 50 ? 0.0f : 0.05f * static_cast<float>(50 - f));
    return {
        {"switch-half", 60, false, held(60, {{0, 1.5f}, {30, 0.75f}})},
        {"switch-dim", 60, false, held(60, {{0, 1.5f}, {30, 1.2f}})},
        {"switch-on", 60, false, held(60, {{0, 0.0f}, {30, 1.5f}})},
        {"fade", 60, false, fade},
        {"burst-1", 60, false, held(60, {{0, 1.5f}, {30, 0.0f}, {31, 1.5f}})},
        {"burst-3", 60, false, held(60, {{0, 1.5f}, {30, 0.0f}, {33, 1.5f}})},
        {"camera-switch", 60, true, held(60, {{0, 1.5f}, {30, 0.0f}})},
        {"long-off", 330, false, held(330, {{0, 1.5f}, {30, 0.0f}})},
    };
}

const light& named(const scene& s, const std::string& name) {
    const auto it = std::find_if(s.lights.begin(), s.lights.end(), [&](const light& l) { return l.name == name; });
    INFO(s.name << ": light " << name);
    REQUIRE(it != s.lights.end());
    return *it;
}

}  // namespace

TEST_CASE("each variation scene is light-off with its key light's curve or its camera changed as its name says") {
    const scene base = load_scene_argument("light-off");
    const auto dir = source_dir() / "demo" / "scenes" / "variations";
    for (const variation& v : variations()) {
        INFO(v.name);
        const scene s = load_scene(dir / (v.name + ".json"));
        CHECK(s.name == v.name);
        CHECK(!s.description.empty());
        CHECK(s.frames == v.frames);
        std::ifstream in(dir / (v.name + ".json"));
        CHECK(nlohmann::json::parse(in).value("$schema", "") == "../scene.schema.json");

        // light-off's statuette, material and fill light.
        CHECK(s.mm_per_unit == base.mm_per_unit);
        REQUIRE(s.meshes.size() == base.meshes.size());
        CHECK(s.meshes[0].vertices.size() == base.meshes[0].vertices.size());
        CHECK(s.meshes[0].indices == base.meshes[0].indices);
        REQUIRE(s.materials.size() == 1u);
        CHECK(s.materials[0].albedo == base.materials[0].albedo);
        CHECK(s.materials[0].mean_free_path_mm == base.materials[0].mean_free_path_mm);
        REQUIRE(s.lights.size() == 2u);
        const light& fill = named(s, "fill");
        CHECK(fill.intensity.is_constant());
        CHECK(fill.intensity.at(0) == named(base, "fill").intensity.at(0));
        CHECK(named(s, "key").casts_shadow);

        const curve& key = named(s, "key").intensity;
        for (const auto& [frame, value] : v.key) {
            INFO("frame " << frame);
            CHECK(std::fabs(key.at(frame) - value) <= 1e-6f);
        }

        CHECK(s.view.is_static() == !v.camera_moves);
        if (!v.camera_moves) {
            CHECK(s.view.at(0) == base.view.at(0));
        } else {
            // A slow orbit at light-off's distance and height: each frame moves the eye a little, the whole
            // sequence turns it by 20 degrees.
            const auto [first_eye, first_target] = s.view.at(0);
            const auto [last_eye, last_target] = s.view.at(v.frames - 1);
            CHECK(first_target == last_target);
            const float turn = std::acos(glm::dot(glm::normalize(glm::vec2(first_eye.x, first_eye.z)),
                                                  glm::normalize(glm::vec2(last_eye.x, last_eye.z))));
            CHECK(std::fabs(glm::degrees(turn) - 20.0f) < 0.1f);
            for (int f = 1; f < v.frames; ++f)
                CHECK(glm::length(s.view.at(f).first - s.view.at(f - 1).first) < 0.02f);
        }
    }
}

TEST_CASE("the variation scenes are not built-in scenes: --list-scenes keeps to demo/scenes/*.json") {
    for (const variation& v : variations()) {
        INFO(v.name);
        const auto names = builtin_scene_names();
        CHECK(std::find(names.begin(), names.end(), v.name) == names.end());
    }
}

TEST_CASE("the validation scenes are a skin close-up with light-off's lights and switch, one still, one orbiting") {
    // demo/scenes/validation/: what differs from light-off is the material (Burley's skin), the scale (a
    // life-size head) and the framing; what they share is the event (light-off's key light, off at frame 30).
    const scene base = load_scene_argument("light-off");
    const auto dir = source_dir() / "demo" / "scenes" / "validation";
    for (const auto& [name, camera_moves] : {std::pair<std::string, bool>{"skin-close", false}, {"skin-orbit", true}}) {
        INFO(name);
        const scene s = load_scene(dir / (name + ".json"));
        CHECK(s.name == name);
        CHECK(!s.description.empty());
        CHECK(s.frames == 60);
        std::ifstream in(dir / (name + ".json"));
        CHECK(nlohmann::json::parse(in).value("$schema", "") == "../scene.schema.json");
        const auto names = builtin_scene_names();
        CHECK(std::find(names.begin(), names.end(), name) == names.end());

        CHECK(s.mm_per_unit == 250.0f);
        REQUIRE(s.materials.size() == 1u);
        CHECK(s.materials[0].mean_free_path_mm == glm::vec3(3.67f, 1.37f, 0.68f));
        CHECK(s.materials[0].mean_free_path_mm != base.materials[0].mean_free_path_mm);
        REQUIRE(s.meshes.size() == 1u);
        CHECK(s.meshes[0].indices == base.meshes[0].indices);

        REQUIRE(s.lights.size() == 2u);
        CHECK(named(s, "fill").intensity.is_constant());
        CHECK(named(s, "fill").intensity.at(0) == named(base, "fill").intensity.at(0));
        CHECK(named(s, "key").casts_shadow);
        for (int f = 0; f < s.frames; ++f) {
            INFO("frame " << f);
            CHECK(named(s, "key").intensity.at(f) == named(base, "key").intensity.at(f));
        }

        CHECK(s.view.is_static() == !camera_moves);
        // Closer than light-off's camera: the head fills the image.
        CHECK(glm::length(s.view.at(30).first - s.view.at(30).second) < 0.6f * glm::length(base.view.at(0).first - base.view.at(0).second));
        if (camera_moves) {
            const auto [first_eye, first_target] = s.view.at(0);
            const auto [last_eye, last_target] = s.view.at(s.frames - 1);
            CHECK(first_target == last_target);
            const glm::vec2 a = glm::vec2(first_eye.x, first_eye.z) - glm::vec2(first_target.x, first_target.z);
            const glm::vec2 b = glm::vec2(last_eye.x, last_eye.z) - glm::vec2(last_target.x, last_target.z);
            CHECK(std::fabs(glm::degrees(std::acos(glm::dot(glm::normalize(a), glm::normalize(b)))) - 20.0f) < 0.1f);
            CHECK(std::fabs(glm::length(a) - glm::length(b)) < 1e-3f);
        }
    }
}

TEST_CASE("the tabletop validation scene is mixed with its key light switching off at frame 30") {
    // demo/scenes/validation/mixed-off.json: what differs from light-off is nearly everything but the event
    // (several objects and materials, jade among them, thin edges in front of a lit floor); what differs from the
    // built-in `mixed` is the length and the key light's step.
    const scene base = load_scene_argument("mixed");
    const auto path = source_dir() / "demo" / "scenes" / "validation" / "mixed-off.json";
    const scene s = load_scene(path);
    CHECK(s.name == "mixed-off");
    CHECK(!s.description.empty());
    CHECK(s.frames == 60);
    std::ifstream in(path);
    CHECK(nlohmann::json::parse(in).value("$schema", "") == "../scene.schema.json");
    const auto names = builtin_scene_names();
    CHECK(std::find(names.begin(), names.end(), "mixed-off") == names.end());

    CHECK(s.mm_per_unit == base.mm_per_unit);
    REQUIRE(s.meshes.size() == base.meshes.size());
    for (std::size_t i = 0; i < s.meshes.size(); ++i) CHECK(s.meshes[i].indices == base.meshes[i].indices);
    REQUIRE(s.materials.size() == base.materials.size());
    for (std::size_t i = 0; i < s.materials.size(); ++i)
        CHECK(s.materials[i].mean_free_path_mm == base.materials[i].mean_free_path_mm);
    CHECK(s.objects.size() == base.objects.size());
    CHECK(s.view.is_static());
    CHECK(s.view.at(0) == base.view.at(0));

    REQUIRE(s.lights.size() == 2u);
    CHECK(named(s, "rim").intensity.is_constant());
    CHECK(named(s, "rim").intensity.at(0) == named(base, "rim").intensity.at(0));
    CHECK(named(s, "key").casts_shadow);
    for (const auto& [f, v] : held(60, {{0, 2.5f}, {30, 0.0f}})) {
        INFO("frame " << f);
        CHECK(named(s, "key").intensity.at(f) == v);
    }
}

TEST_CASE("the validation scenes added after the parameters were chosen keep what their descriptions promise") {
    // demo/scenes/validation/{cow-orbit, wax-steps, jade-sinus}: other meshes, materials, scales and events than
    // any scene a parameter was chosen on. Each is pinned to its event (every frame of each light's curve) and its
    // camera, so that a light one frame off or a camera that stops moving fails.
    const auto dir = source_dir() / "demo" / "scenes" / "validation";
    const auto names = builtin_scene_names();
    auto load_checked = [&](const std::string& name, int frames) {
        INFO(name);
        const scene s = load_scene(dir / (name + ".json"));
        CHECK(s.name == name);
        CHECK(!s.description.empty());
        CHECK(s.frames == frames);
        std::ifstream in(dir / (name + ".json"));
        CHECK(nlohmann::json::parse(in).value("$schema", "") == "../scene.schema.json");
        CHECK(std::find(names.begin(), names.end(), name) == names.end());
        return s;
    };
    auto sss_materials = [](const scene& s) {
        return std::count_if(s.materials.begin(), s.materials.end(),
                             [](const material& m) { return m.type == material::kind::sss; });
    };

    SECTION("cow-orbit: still lights, a textured SSS material, the camera orbiting by 20 degrees") {
        const scene s = load_checked("cow-orbit", 60);
        CHECK(s.mm_per_unit == 120.0f);
        CHECK(sss_materials(s) == 1);
        CHECK(s.materials.size() == 2u);
        const auto textured = std::find_if(s.materials.begin(), s.materials.end(),
                                           [](const material& m) { return m.albedo_texture >= 0; });
        REQUIRE(textured != s.materials.end());
        CHECK(textured->type == material::kind::sss);
        REQUIRE(s.lights.size() == 2u);
        for (const light& l : s.lights) CHECK(l.intensity.is_constant());
        CHECK(named(s, "key").casts_shadow);
        CHECK_FALSE(s.view.is_static());
        const auto [first_eye, first_target] = s.view.at(0);
        const auto [last_eye, last_target] = s.view.at(s.frames - 1);
        CHECK(first_target == last_target);
        CHECK(first_eye.y == last_eye.y);
        const glm::vec2 a = glm::vec2(first_eye.x, first_eye.z) - glm::vec2(first_target.x, first_target.z);
        const glm::vec2 b = glm::vec2(last_eye.x, last_eye.z) - glm::vec2(last_target.x, last_target.z);
        CHECK(std::fabs(glm::degrees(std::acos(glm::dot(glm::normalize(a), glm::normalize(b)))) - 20.0f) < 0.1f);
        CHECK(std::fabs(glm::length(a) - glm::length(b)) < 1e-3f);
    }

    SECTION("wax-steps: a wide wax kernel under a key that steps down, up and off, 20 frames apart") {
        const scene s = load_checked("wax-steps", 80);
        REQUIRE(s.materials.size() == 1u);
        CHECK(s.materials[0].mean_free_path_mm == glm::vec3(6.0f, 5.0f, 4.0f));
        CHECK(s.view.is_static());
        REQUIRE(s.lights.size() == 2u);
        CHECK(named(s, "fill").intensity.is_constant());
        CHECK(named(s, "key").casts_shadow);
        for (const auto& [f, v] : held(80, {{0, 1.5f}, {20, 0.3f}, {40, 1.5f}, {60, 0.0f}})) {
            INFO("frame " << f);
            CHECK(named(s, "key").intensity.at(f) == v);
        }
    }

    SECTION("jade-sinus: two SSS materials, a steady key and a light on a 40-frame sinusoid from 0 to 4") {
        const scene s = load_checked("jade-sinus", 60);
        CHECK(sss_materials(s) == 2);
        CHECK(s.view.is_static());
        REQUIRE(s.lights.size() == 2u);
        CHECK(named(s, "key").intensity.is_constant());
        CHECK(named(s, "key").casts_shadow);
        for (int f = 0; f < s.frames; ++f) {
            INFO("frame " << f);
            const double expected = 2.0 + 2.0 * std::sin(2.0 * 3.14159265358979 * f / 40.0);
            CHECK(std::fabs(named(s, "party").intensity.at(f) - expected) < 1e-5);
        }
    }
}
