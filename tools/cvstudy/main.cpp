// SPDX-License-Identifier: MIT
// emcv-cvstudy: the per-pixel study behind the cv method's residual variance (docs/renderer.md).
// Prints one Markdown table per light curve: mean samples and error of SPVG, the two residual-variance
// choices of the control variate for eta in {0.05, 0.1, 0.2}, and cv-notex, over the measured window.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "cvstudy_simulation.hpp"

namespace {

using namespace emcv::cvstudy;

const char* usage =
    "usage: emcv-cvstudy [--pixels N] [--seed S] [--half-state all|means]\n"
    "  Simulates one SSS pixel's adaptive-sampling loop (Xie & Olano 2021, section 5) over N pixels (default 400)\n"
    "  with fixed seeds and prints, per light curve, mean samples and PSNR over the 30 frames from the\n"
    "  switch / first burst, for spvg, the cv residual-variance choices and cv-notex.\n"
    "  --half-state all|means rounds every history field, or only the means, to binary16 after each\n"
    "  frame (what an RGBA16F history keeps).\n";

/// A whole positive integer in [1, max]; throws std::invalid_argument naming the flag otherwise.
std::uint64_t parse_count(const std::string& flag, const std::string& text, std::uint64_t max) {
    std::size_t used = 0;
    unsigned long long v = 0;
    try {
        v = std::stoull(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != text.size() || text.empty() || text[0] == '-' || v < 1 || v > max)
        throw std::invalid_argument(flag + ": expected a whole number in 1.." + std::to_string(max) + ", got '" +
                                    text + "'");
    return v;
}

std::string fixed(double v, int digits) {
    if (!std::isfinite(v)) return v > 0 ? "inf" : "nan";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

void print_table(const char* title, light_curve curve, const std::vector<method_config>& methods,
                 const study_config& config) {
    const auto results = run_study(curve, methods, config);
    const method_result& spvg = results.front();
    std::cout << "\n### " << title << "\n\n"
              << "| method | mean N | N / spvg's | PSNR dB | PSNR - spvg's dB | frames with N = 0 |\n"
              << "|---|---|---|---|---|---|\n";
    for (const method_result& r : results) {
        std::cout << "| " << r.method << " | " << fixed(r.mean_n, 2) << " | " << fixed(r.mean_n / spvg.mean_n, 3)
                  << " | " << fixed(r.psnr_db, 2) << " | " << fixed(r.psnr_db - spvg.psnr_db, 2) << " | "
                  << fixed(100.0 * r.zero_share, 1) << "% |\n";
    }
}

}  // namespace

int main(int argc, char** argv) {
    study_config config;
    try {
        for (int i = 1; i < argc; ++i) {
            const std::string a = argv[i];
            if (a == "--help" || a == "-h") {
                std::cout << usage;
                return 0;
            }
            if (a != "--pixels" && a != "--seed" && a != "--half-state") throw std::invalid_argument("unknown flag '" + a + "'");
            if (i + 1 >= argc) throw std::invalid_argument(a + ": missing value");
            const std::string v = argv[++i];
            if (a == "--half-state") {
                if (v != "all" && v != "means") throw std::invalid_argument("--half-state: expected all or means, got '" + v + "'");
                config.half_state = v == "all" ? study_config::half_fields::all : study_config::half_fields::means;
            } else if (a == "--pixels") config.pixels = static_cast<std::size_t>(parse_count(a, v, 1000000));
            else config.seed = parse_count(a, v, UINT64_MAX);
        }
    } catch (const std::invalid_argument& e) {
        std::cerr << "emcv-cvstudy: " << e.what() << '\n';
        return 2;
    }

    using emcv::sampling_estimator;
    std::vector<method_config> methods = {{sampling_estimator::spvg, 0.2f}};
    for (float eta : {0.05f, 0.1f, 0.2f}) methods.push_back({sampling_estimator::cv, eta, -1, true});
    for (float eta : {0.05f, 0.1f, 0.2f}) methods.push_back({sampling_estimator::cv, eta});
    methods.push_back({sampling_estimator::cv_notex, 0.2f});
    // The plain n_min = 0 the paper describes, for comparison with the renderer's rule.
    for (float eta : {0.05f, 0.2f}) methods.push_back({sampling_estimator::cv, eta, 0});
    methods.push_back({sampling_estimator::cv_notex, 0.2f, 0});

    std::cout << "emcv-cvstudy: " << config.pixels << " pixels, seed " << config.seed << ", target "
              << config.target << ", N_max " << config.n_max << "; window: " << config.window_frames
              << " frames after " << config.warmup_frames << " warm-up frames; history state in "
              << (config.half_state == study_config::half_fields::none
                      ? "fp32"
                      : config.half_state == study_config::half_fields::all ? "binary16" : "fp32, means in binary16")
              << "\n";
    print_table("light-off: switch 1 -> 0.25 (the 30 frames from the switch)", light_curve::switch_off, methods,
                config);
    print_table("flicker: bursts of 2 frames at 1 over 0.3, every 10 frames", light_curve::flicker, methods, config);
    print_table("club: sinusoid 0.6 + 0.4 sin(2 pi t / 24)", light_curve::sinusoid, methods, config);
    print_table("static: constant light", light_curve::constant, methods, config);
    config.sub_pixel = true;
    print_table("far: sub-pixel kernels (f = G exactly), constant light", light_curve::constant, methods, config);
    return 0;
}
