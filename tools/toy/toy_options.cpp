// SPDX-License-Identifier: MIT
#include "toy_options.hpp"

#include "cli/command_line.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace emcv::toy {
namespace {

[[noreturn]] void fail(const std::string& flag, const std::string& what, const std::string& value) {
    throw usage_error(flag + ": " + what + ", got '" + value + "'");
}

std::uint64_t parse_unsigned(const std::string& flag, const std::string& value) {
    if (value.empty() || value.find_first_not_of("0123456789") != std::string::npos)
        fail(flag, "expected a non-negative integer", value);
    errno = 0;
    char* end = nullptr;
    const unsigned long long v = std::strtoull(value.c_str(), &end, 10);
    if (errno == ERANGE || *end != '\0') fail(flag, "integer out of range", value);
    return static_cast<std::uint64_t>(v);
}

double parse_real(const std::string& flag, const std::string& value) {
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (value.empty() || end == value.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
        fail(flag, "expected a finite number", value);
    return v;
}

double parse_eta(const std::string& flag, const std::string& value) {
    const double eta = parse_real(flag, value);
    if (!(eta > 0.0 && eta <= 1.0)) fail(flag, "must lie in (0, 1]", value);
    return eta;
}

std::size_t parse_at_least(const std::string& flag, const std::string& value, std::uint64_t minimum) {
    const std::uint64_t v = parse_unsigned(flag, value);
    if (v < minimum) fail(flag, "must be at least " + std::to_string(minimum), value);
    if (v > 100000000ull) fail(flag, "must be at most 100000000", value);
    return static_cast<std::size_t>(v);
}

}  // namespace

std::string usage_text() {
    return "usage: emcv-toy [options]\n"
           "Reproduces the toy experiment of Xie & Olano 2021, supplementary section 3 (Table 1, Figs. 1-2).\n"
           "\n"
           "  --scenario static|dynamic|both  which light h(t) to run (default both)\n"
           "  --seeds N          number of independent runs, N >= 1 (default 1000)\n"
           "  --seed S           first seed; runs use S, S+1, ..., S+N-1 (default 1)\n"
           "  --frames F         frames per run, F >= 25 (default 100; Table 1 averages frames 25..F)\n"
           "  --spp K            correlated samples per frame, K >= 2 (default 16)\n"
           "  --eta-cov E        EMCM weight over frames, in (0, 1] (default 0.05)\n"
           "  --eta-res E        weight of each residual's moving variance, in (0, 1] (default 0.2)\n"
           "  --sf-ema-eta E     EMA weight smoothing alpha_SF for Res_SF+EMA, in (0, 1] (default 0.05)\n"
           "  --t0 0|1           time t of frame 1 in h2(t) = 1 + 3 sin(t/10) (default 0)\n"
           "  --first-frame zero|primed  frame 1 uses alpha = 0, or feeds the estimators before its own\n"
           "                     residual (default primed)\n"
           "  --gt-alpha paper|analytic  alpha* of Res_GT: 0.477/1.388 or 0.4767/2 ln 2 (default paper)\n"
           "  --csv DIR          write DIR/static.csv and DIR/dynamic.csv (per-frame, first seed's run)\n"
           "  --json             print one JSON object instead of the table\n"
           "  --help             print this text\n"
           "Bad input exits with status 2.\n";
}

toy_options parse_options(const std::vector<std::string>& args) {
    toy_options o;
    for (std::size_t i = 0; i < args.size(); ++i) {
        cli::flag_argument<usage_error> argument(args, i);
        const std::string& flag = argument.name();
        const std::string& value = argument.inline_value();
        const bool has_inline_value = argument.has_inline_value();
        const auto next_value = [&] { return argument.value(); };
        if (flag == "--help" || flag == "-h") {
            o.help = true;
        } else if (flag == "--json") {
            o.json = true;
        } else if (flag == "--scenario") {
            const std::string v = next_value();
            if (v == "static") { o.run_static = true; o.run_dynamic = false; }
            else if (v == "dynamic") { o.run_static = false; o.run_dynamic = true; }
            else if (v == "both") { o.run_static = true; o.run_dynamic = true; }
            else fail(flag, "expected static, dynamic or both", v);
        } else if (flag == "--seeds") {
            o.seeds = parse_at_least(flag, next_value(), 1);
        } else if (flag == "--seed") {
            o.first_seed = parse_unsigned(flag, next_value());
        } else if (flag == "--frames") {
            o.config.frames = parse_at_least(flag, next_value(), o.config.window_first);
        } else if (flag == "--spp") {
            o.config.spp = parse_at_least(flag, next_value(), 2);
        } else if (flag == "--eta-cov") {
            o.config.eta_cov = parse_eta(flag, next_value());
        } else if (flag == "--eta-res") {
            o.config.eta_res = parse_eta(flag, next_value());
        } else if (flag == "--sf-ema-eta") {
            o.config.eta_sf_ema = parse_eta(flag, next_value());
        } else if (flag == "--t0") {
            const std::string v = next_value();
            if (v == "0") o.config.t0 = 0;
            else if (v == "1") o.config.t0 = 1;
            else fail(flag, "expected 0 or 1", v);
        } else if (flag == "--first-frame") {
            const std::string v = next_value();
            if (v == "zero") o.config.first = first_frame::zero_alpha;
            else if (v == "primed") o.config.first = first_frame::primed;
            else fail(flag, "expected zero or primed", v);
        } else if (flag == "--gt-alpha") {
            const std::string v = next_value();
            if (v == "paper") o.config.gt = gt_alpha_source::paper;
            else if (v == "analytic") o.config.gt = gt_alpha_source::analytic;
            else fail(flag, "expected paper or analytic", v);
        } else if (flag == "--csv") {
            o.csv_dir = next_value();
            if (o.csv_dir.empty()) fail(flag, "expected a directory", o.csv_dir);
        } else {
            throw usage_error("unknown flag '" + args[i] + "' (see --help)");
        }
        if (has_inline_value && (flag == "--help" || flag == "-h" || flag == "--json"))
            fail(flag, "takes no value", value);
    }
    return o;
}

}  // namespace emcv::toy
