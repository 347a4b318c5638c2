// SPDX-License-Identifier: MIT
#include "eval_options.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <sstream>

#include "render/tunables.hpp"

namespace emcv::eval {
namespace {

long parse_integer(const std::string& flag, const std::string& text, long low, long high) {
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno != 0 || v < low || v > high)
        throw usage_error(flag + ": expected an integer in " + std::to_string(low) + ".." + std::to_string(high) +
                          ", got '" + text + "'");
    return v;
}

std::vector<std::string> split(const std::string& text) {
    std::vector<std::string> items;
    std::stringstream s(text);
    for (std::string item; std::getline(s, item, ',');) items.push_back(item);
    return items;
}

}  // namespace

std::string usage_text() {
    return "usage: emcv-eval --method M[,M...] [--scene FILE|NAME] [--size WxH] [--frames N] [--sss-scale K]\n"
           "                 [--seed S] [--heatmaps F[,F...] --heatmap-dir DIR] [--approximate-cdf]\n"
           "                 [--spp-budget B | --target-variance V] [--timing auto|wall|gpu]\n"
           "                 [--resolve none|taa] [--jitter] [--define NAME=VALUE ...]\n"
           "Renders the methods side by side, frame by frame (no reference), and prints one CSV row per frame\n"
           "and method: scene,width,height,sss_scale,method,frame,sss_ms,frame_ms,mean_spp,max_spp,sss_pixels,lights,\n"
           "sampling,timing,resolve (lights: name=intensity;... of the scene's light curves at the frame;\n"
           "sampling: the adaptive methods' mode, \"budget B spp\" or \"target variance V\"; timing: the clock of\n"
           "sss_ms and frame_ms, gpu or wall; resolve: taa or none, the reference never resolves). Under GPU\n"
           "timestamps rows are printed once every method's stamps arrived.\n"
           "--sss-scale multiplies every scattering material's mean free path (the radius on screen).\n"
           "--heatmaps writes <method>.f<F>.samples.csv, .mask.csv (1 at SSS pixels; and .alpha.csv for cv)\n"
           "under DIR, top row first.\n"
           "--define sets a tunable of the port headers for every shader (as emcv-demo --define).\n" +
           demo::sampling_flags_help() + demo::timing_flag_help() + demo::resolve_flag_help() +
           "Methods (--method takes these names; emcv-demo --list-methods prints them for scripts):\n" +
           demo::method_help_lines(2);
}

options parse_options(const std::vector<std::string>& args) {
    options o;
    std::string sampling_flag;  // --spp-budget or --target-variance, once seen
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& flag = args[i];
        if (flag == "--help" || flag == "-h") {
            o.help = true;
            continue;
        }
        if (flag == "--approximate-cdf") {
            o.approximate_cdf = true;
            continue;
        }
        if (flag == "--jitter") {
            o.jitter = true;
            continue;
        }
        if (flag.rfind("--", 0) != 0) throw usage_error("unexpected argument '" + flag + "'");
        static const char* const known[] = {"--scene", "--method", "--size", "--frames", "--seed", "--sss-scale",
                                            "--heatmaps", "--define", "--spp-budget", "--target-variance", "--timing",
                                            "--resolve", "--heatmap-dir"};
        if (std::find(std::begin(known), std::end(known), flag) == std::end(known))
            throw usage_error("unknown option '" + flag + "'");
        if (i + 1 >= args.size()) throw usage_error(flag + ": missing value");
        const std::string& value = args[++i];
        if (flag == "--scene") {
            o.scene = value;
        } else if (flag == "--method") {
            for (const std::string& name : split(value)) {
                const auto m = demo::parse_method(name);
                if (!m) throw usage_error("--method: unknown method '" + name + "'");
                o.methods.push_back(*m);
            }
        } else if (flag == "--size") {
            const auto x = value.find('x');
            if (x == std::string::npos) throw usage_error("--size: expected WxH, got '" + value + "'");
            o.width = static_cast<int>(parse_integer("--size", value.substr(0, x), 1, 8192));
            o.height = static_cast<int>(parse_integer("--size", value.substr(x + 1), 1, 8192));
        } else if (flag == "--frames") {
            o.frames = static_cast<int>(parse_integer(flag, value, 1, 100000));
        } else if (flag == "--seed") {
            o.seed = static_cast<unsigned>(parse_integer(flag, value, 0, 2147483647));
        } else if (flag == "--sss-scale") {
            char* end = nullptr;
            const float k = std::strtof(value.c_str(), &end);
            if (value.empty() || *end != '\0' || !std::isfinite(k) || k <= 0.0f || k > 1000.0f)
                throw usage_error("--sss-scale: expected a number in (0, 1000], got '" + value + "'");
            o.sss_scale = k;
        } else if (flag == "--define") {
            try {
                demo::add_define(o.defines, value);
            } catch (const demo::tunable_error& e) {
                throw usage_error(e.what());
            }
        } else if (flag == "--spp-budget" || flag == "--target-variance") {
            try {
                demo::add_sampling_flag(o.defines, flag, value, sampling_flag);
            } catch (const demo::tunable_error& e) {
                throw usage_error(e.what());
            }
        } else if (flag == "--timing") {
            try {
                o.timing = demo::parse_timing_flag(value);
            } catch (const demo::timing_error& e) {
                throw usage_error(e.what());
            }
        } else if (flag == "--resolve") {
            try {
                o.resolve = demo::parse_resolve_flag(value);
            } catch (const demo::resolve_error& e) {
                throw usage_error(e.what());
            }
        } else if (flag == "--heatmaps") {
            for (const std::string& f : split(value)) o.heatmap_frames.push_back(static_cast<int>(parse_integer(flag, f, 0, 100000)));
        } else {  // --heatmap-dir, the last of `known`
            o.heatmap_dir = value;
        }
    }
    if (o.help) return o;
    if (o.methods.empty()) throw usage_error("--method: required");
    if (!o.heatmap_frames.empty() && o.heatmap_dir.empty()) throw usage_error("--heatmaps needs --heatmap-dir DIR");
    try {
        demo::check_jitter_flag(o.jitter, o.resolve);
    } catch (const demo::resolve_error& e) {
        throw usage_error(e.what());
    }
    try {
        demo::check_tunables(o.defines);
    } catch (const demo::tunable_error& e) {
        throw usage_error(e.what());
    }
    return o;
}

}  // namespace emcv::eval
