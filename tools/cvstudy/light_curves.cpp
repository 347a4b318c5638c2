// SPDX-License-Identifier: MIT
// emcv-light-curves: each light's intensity at every frame of a scene, as CSV (frame,light,intensity), from
// the scene's own curves (demo/scene), for the plots of tools/cvstudy/adaptive_report.py.
#include <exception>
#include <iostream>
#include <string>

#include "scene/load.hpp"

namespace {

const char* const usage = "usage: emcv-light-curves SCENE (a file or a built-in name)\n";

int usage_error(const std::string& problem) {
    std::cerr << "emcv-light-curves: " << problem << '\n' << usage;
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
        std::cout << usage;
        return 0;
    }
    if (argc < 2) return usage_error("missing SCENE");
    for (int i = 1; i < argc; ++i)
        if (argv[i][0] == '-') return usage_error(std::string("unknown flag '") + argv[i] + "'");
    if (argc > 2) return usage_error(std::string("one SCENE only, got also '") + argv[2] + "'");
    try {
        const emcv::demo::scene s = emcv::demo::load_scene_argument(argv[1]);
        std::cout << "frame,light,intensity\n";
        for (int f = 0; f < s.frames; ++f)
            for (const emcv::demo::light& l : s.lights) std::cout << f << ',' << l.name << ',' << l.intensity.at(f) << '\n';
    } catch (const std::exception& e) {
        std::cerr << "emcv-light-curves: " << e.what() << '\n';
        return 2;
    }
    return 0;
}
