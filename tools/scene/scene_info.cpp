// SPDX-License-Identifier: MIT
// emcv-scene-info: one table row per scene (built-in, or the files given): what it holds and how large its
// scattering is on screen (docs/scenes.md quotes this table).
//
//   emcv-scene-info [--size WxH] [SCENE...]      (SCENE: a file or a built-in name; none: every built-in)
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "scene/footprint.hpp"
#include "scene/load.hpp"

namespace {

using namespace emcv::demo;

bool parse_size(const std::string& text, int& width, int& height) {
    int consumed = 0;
    if (std::sscanf(text.c_str(), "%dx%d%n", &width, &height, &consumed) != 2) return false;
    return consumed == static_cast<int>(text.size()) && width > 0 && height > 0 && width <= 16384 && height <= 16384;
}

void print_row(const scene& s, int width, int height) {
    std::size_t triangles = 0;
    for (const object& o : s.objects) triangles += s.meshes[static_cast<std::size_t>(o.mesh)].indices.size() / 3u;
    const auto shadow_casters = std::count_if(s.lights.begin(), s.lights.end(), [](const light& l) { return l.casts_shadow; });
    const auto animated = std::count_if(s.lights.begin(), s.lights.end(), [](const light& l) { return !l.intensity.is_constant(); });
    const auto sss_objects = std::count_if(s.objects.begin(), s.objects.end(), [&](const object& o) {
        return s.materials[static_cast<std::size_t>(o.material)].scatters();
    });
    float r_min = 0.0f, r_max = 0.0f;
    const auto footprints = scattering_footprints(s, 0, width, height);
    for (std::size_t i = 0; i < footprints.size(); ++i) {
        const float r = footprints[i].radius_pixels;
        r_min = i == 0 ? r : std::min(r_min, r);
        r_max = i == 0 ? r : std::max(r_max, r);
    }
    char radius[64] = "-";
    if (!footprints.empty()) std::snprintf(radius, sizeof radius, "%.2f - %.2f", static_cast<double>(r_min), static_cast<double>(r_max));
    std::printf("| `%s` | %d | %zu | %ld | %zu | %ld | %ld | %s | %zu | %s |\n", s.name.c_str(), s.frames, s.objects.size(),
                static_cast<long>(sss_objects), s.lights.size(), static_cast<long>(shadow_casters),
                static_cast<long>(animated), s.view.is_static() ? "no" : "yes", triangles, radius);
}

}  // namespace

int main(int argc, char** argv) {
    int width = 256, height = 256;
    std::vector<std::string> names;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--size") {
            if (i + 1 >= argc || !parse_size(argv[i + 1], width, height)) {
                std::cerr << "emcv-scene-info: --size expects WxH (e.g. 256x256)\n";
                return 2;
            }
            ++i;
        } else if (a == "--help" || a == "-h") {
            std::cout << "usage: emcv-scene-info [--size WxH] [SCENE...]\n";
            return 0;
        } else if (!a.empty() && a[0] == '-') {
            std::cerr << "emcv-scene-info: unknown flag " << a << " (--help for usage)\n";
            return 2;
        } else {
            names.push_back(a);
        }
    }
    if (names.empty()) names = builtin_scene_names();
    // Every scene is loaded before anything is printed: a bad one leaves no partial table.
    std::vector<scene> scenes;
    try {
        for (const auto& n : names) scenes.push_back(load_scene_argument(n));
    } catch (const scene_error& e) {
        std::cerr << "emcv-scene-info: " << e.what() << "\n";
        return 2;
    }
    std::printf("| scene | frames | objects | SSS objects | lights | shadow maps | animated lights | camera moves | "
                "triangles | SSS radius at %dx%d (px, 99.7%%) |\n|---|---|---|---|---|---|---|---|---|---|\n",
                width, height);
    for (const scene& s : scenes) print_row(s, width, height);
    return 0;
}
