// SPDX-License-Identifier: MIT
// The built-in scenes (demo/scenes/): each loads, declares the schema, and has the property its name
// promises (docs/scenes.md).
#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <fstream>

#include "scene/footprint.hpp"
#include "scene/load.hpp"
#include "scene_test_support.hpp"

using namespace emcv::demo;
using emcv::test::source_dir;

namespace {

std::size_t shadow_casters(const scene& s) {
    return static_cast<std::size_t>(
        std::count_if(s.lights.begin(), s.lights.end(), [](const light& l) { return l.casts_shadow; }));
}

bool has_curve(const scene& s, curve::kind kind) {
    return std::any_of(s.lights.begin(), s.lights.end(), [&](const light& l) {
        return l.intensity.type == kind && !l.intensity.is_constant();
    });
}

/// r / d at which Burley's CDF reaches 0.997 (solved in "the footprint is 16.6 shape distances ..." below).
constexpr float radius_per_shape_distance = 16.57f;

}  // namespace

TEST_CASE("the built-in scene names are the eight demo scenes, sorted, without the schema") {
    CHECK(builtin_scene_names() ==
          std::vector<std::string>{"club", "far", "flicker", "light-off", "mixed", "moving", "no-sss", "static"});
}

TEST_CASE("every built-in scene loads, declares the schema and describes itself", "[image-files]") {
    for (const auto& name : builtin_scene_names()) {
        INFO(name);
        const scene s = load_scene_argument(name);
        CHECK(s.name == name);
        CHECK(!s.description.empty());
        CHECK(s.frames >= 1);
        CHECK(s.frames <= 60);  // short sequences
        std::ifstream in(builtin_scene_dir() / (name + ".json"));
        const auto j = nlohmann::json::parse(in);
        CHECK(j.value("$schema", "") == "./scene.schema.json");
    }
}

TEST_CASE("each built-in scene has the property its name promises", "[image-files]") {
    const scene light_off = load_scene_argument("light-off");
    // The key light switches off mid-sequence; another light stays on throughout.
    const auto key = std::find_if(light_off.lights.begin(), light_off.lights.end(), [&](const light& l) {
        return l.intensity.at(0) > 0.0f && l.intensity.at(light_off.frames - 1) == 0.0f;
    });
    REQUIRE(key != light_off.lights.end());
    int off_frame = 0;
    while (key->intensity.at(off_frame) > 0.0f) ++off_frame;
    CHECK(off_frame > 0);
    CHECK(off_frame < light_off.frames);
    CHECK(std::any_of(light_off.lights.begin(), light_off.lights.end(), [](const light& l) {
        return l.intensity.is_constant() && l.intensity.at(0) > 0.0f;
    }));

    CHECK(has_curve(load_scene_argument("flicker"), curve::kind::flicker));
    CHECK(has_curve(load_scene_argument("club"), curve::kind::sinusoid));

    const scene mixed = load_scene_argument("mixed");
    const auto scatters = [&](const object& o) { return mixed.materials[static_cast<std::size_t>(o.material)].scatters(); };
    CHECK(std::any_of(mixed.objects.begin(), mixed.objects.end(), scatters));
    CHECK_FALSE(std::all_of(mixed.objects.begin(), mixed.objects.end(), scatters));
    CHECK(std::any_of(mixed.meshes.begin(), mixed.meshes.end(), [](const mesh& m) { return m.name == "floor"; }));

    CHECK_FALSE(load_scene_argument("no-sss").has_sss_material());
    CHECK_FALSE(load_scene_argument("moving").view.is_static());

    // Shadow maps only where they matter; at least one scene without any shadow caster.
    CHECK(shadow_casters(load_scene_argument("far")) == 0u);
    CHECK(shadow_casters(load_scene_argument("no-sss")) == 0u);
    CHECK(shadow_casters(load_scene_argument("static")) == 1u);
    CHECK(shadow_casters(mixed) == 1u);
    CHECK(shadow_casters(light_off) == 1u);
}

TEST_CASE("scattering spans 1.5 to 3 pixels of shape distance at 256 x 256, except in far where it is under a pixel",
          "[image-files]") {
    // The 99.7% radius of the widest channel, about 16.6 d with d = l / s(A) mm, projected at the object's
    // centre. The demo's scenes are built so that scattering matters at their own resolution: d between 1.5
    // and 3 pixels (a 99.7% radius of 24.9 to 49.7 px, docs/scenes.md), at the first and the last frame.
    for (const auto& name : builtin_scene_names()) {
        INFO(name);
        const scene s = load_scene_argument(name);
        for (int frame : {0, s.frames - 1}) {
            for (const scattering_footprint& f : scattering_footprints(s, frame, 256, 256)) {
                INFO(f.object << " at frame " << frame << ": " << f.radius_pixels << " px");
                if (name == "far") {
                    CHECK(f.radius_pixels > 0.0f);
                    CHECK(f.radius_pixels < 1.0f);
                } else {
                    CHECK(f.radius_pixels >= 1.5f * radius_per_shape_distance);
                    CHECK(f.radius_pixels <= 3.0f * radius_per_shape_distance);
                }
            }
        }
    }
}

TEST_CASE("the footprint is 16.6 shape distances of the widest channel") {
    // F(r) = 1 - e^{-r/d}/4 - 3 e^{-r/(3d)}/4 = 0.997 at r / d = 16.57 (solved numerically here: F is increasing).
    double lo = 0.0, hi = 100.0;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        const double cdf = 1.0 - std::exp(-mid) / 4.0 - 3.0 * std::exp(-mid / 3.0) / 4.0;
        (cdf < 0.997 ? lo : hi) = mid;
    }
    const scene s = load_scene_argument("static");
    const material& marble = s.materials[0];
    // Marble: red is the widest channel (largest l and largest A, and l grows faster than s(A) there).
    const double s_red = 3.5 + 100.0 * std::pow(static_cast<double>(marble.albedo.x) - 0.33, 4.0);
    const double d_red = static_cast<double>(marble.mean_free_path_mm.x) / s_red;
    const auto footprints = scattering_footprints(s, 0, 256, 256);
    REQUIRE(footprints.size() == 1u);
    CHECK(std::fabs(static_cast<double>(footprints[0].radius_mm) / (lo * d_red) - 1.0) < 1e-4);
}
