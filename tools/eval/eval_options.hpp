// SPDX-License-Identifier: MIT
// emcv-eval command line: parsing and validation only.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "render/renderer.hpp"

namespace emcv::eval {

class usage_error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct options {
    std::string scene = "light-off";  ///< --scene FILE|NAME
    std::vector<demo::method> methods;  ///< --method M[,M...] (required)
    int width = 128, height = 128;    ///< --size WxH
    int frames = 0;                   ///< --frames N; 0: the scene's length
    float sss_scale = 1.0f;           ///< --sss-scale K: every SSS material's mean free path times K
    unsigned seed = 1;                ///< --seed S
    std::vector<int> heatmap_frames;  ///< --heatmaps F[,F...]: frames whose sample counts (and cv alpha) to dump
    std::filesystem::path heatmap_dir;  ///< --heatmap-dir DIR (required with --heatmaps)
    bool approximate_cdf = false;     ///< --approximate-cdf: SPVG's inverse-CDF fit for the Burley radii
    demo::timing_request timing = demo::timing_request::automatic;  ///< --timing auto|wall|gpu
    demo::resolve_mode resolve = demo::resolve_mode::taa;  ///< --resolve none|taa (its pass is in frame_ms)
    bool jitter = false;              ///< --jitter: sub-pixel camera jitter for the resolve (needs taa)
    /// --define NAME=VALUE (repeatable): port tunables, validated (render/tunables.hpp), later ones win.
    std::vector<std::pair<std::string, std::string>> defines;
    bool help = false;
};

options parse_options(const std::vector<std::string>& args);
std::string usage_text();

}  // namespace emcv::eval
