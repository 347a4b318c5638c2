// SPDX-License-Identifier: MIT
#include "tunables.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <emcv/port/history.h>
#include <emcv/port/resolve.h>

namespace emcv::demo {

const std::vector<tunable>& tunables() {
    using t = tunable::type;
    static const std::vector<tunable> all{
        {"EMCV_HISTORY_TARGET", t::real, 0.0, 1.0, true, "quality mode: the output variance aimed at",
         EMCV_HISTORY_TARGET},
        {"EMCV_HISTORY_SPP_BUDGET", t::real, 0.0, 1024.0, false, "budget mode when > 0: mean samples per SSS pixel",
         EMCV_HISTORY_SPP_BUDGET},
        {"EMCV_HISTORY_PLAN_AHEAD", t::integer, 0, 1, false,
         "budget mode: 1 plans a frame that shows the last frame's view in that frame's burley pass (no samples pass)",
         EMCV_HISTORY_PLAN_AHEAD},
        {"EMCV_HISTORY_UPDATE_PERIOD", t::integer, 1, 16, false,
         "budget mode, planned ahead: update the history on one frame in M while view and lights stay still",
         EMCV_HISTORY_UPDATE_PERIOD},
        {"EMCV_HISTORY_N_MAX", t::integer, 1, 1024, false, "most samples per pixel and frame", EMCV_HISTORY_N_MAX},
        {"EMCV_HISTORY_N_MIN", t::integer, 1, 1024, false, "fewest samples of a pixel that scatters", EMCV_HISTORY_N_MIN},
        {"EMCV_HISTORY_ETA_MOVING", t::real, 0.0, 0.5, true, "moving mean/variance weight (spvg, cv-notex)",
         EMCV_HISTORY_ETA_MOVING},
        {"EMCV_HISTORY_ETA_EMCM", t::real, 0.0, 0.5, true, "EMCM weight (cv)", EMCV_HISTORY_ETA_EMCM},
        {"EMCV_HISTORY_BLOCK", t::integer, 1, 4, false,
         "the statistics' grain: one history texel and one N per K x K pixels (1, 2 or 4)", EMCV_HISTORY_BLOCK},
        {"EMCV_HISTORY_MAX_COUNT", t::unsigned_integer, 2, 2048, false, "saturating frame count of a texel",
         double(EMCV_HISTORY_MAX_COUNT)},
        {"EMCV_HISTORY_FOOTPRINT_RADIUS_PER_D", t::real, 0.0, 100.0, true, "kernel radius per shape distance",
         EMCV_HISTORY_FOOTPRINT_RADIUS_PER_D},
        {"EMCV_RESOLVE_BLEND", t::real, 0.0, 1.0, true, "temporal resolve: weight of the current frame",
         EMCV_RESOLVE_BLEND},
        {"EMCV_RESOLVE_CLIP_SIGMA", t::real, 0.0, 4.0, true, "temporal resolve: clip box half-width in std devs",
         EMCV_RESOLVE_CLIP_SIGMA},
        {"EMCV_RESOLVE_NOISE_SIGMA", t::real, 0.0, 16.0, true,
         "temporal resolve: noise box half-width in std devs of the frame's noise", EMCV_RESOLVE_NOISE_SIGMA},
        {"EMCV_RESOLVE_GUIDE", t::integer, 0, 1, false, "temporal resolve: 1 moves the history by the guide's change",
         EMCV_RESOLVE_GUIDE},
        {"EMCV_RESOLVE_GUIDE_TAPS", t::integer, 0, 64, false,
         "temporal resolve: taps of the guide's fixed estimate of the scattered light (0: the unscattered light)",
         EMCV_RESOLVE_GUIDE_TAPS},
    };
    return all;
}

namespace {

[[noreturn]] void fail(std::string_view text, const std::string& why) {
    throw tunable_error("--define: " + why + ", got '" + std::string(text) + "'");
}

/// The tunable called `name`, or nullptr.
const tunable* find_tunable(std::string_view name) {
    for (const tunable& t : tunables())
        if (t.name == name) return &t;
    return nullptr;
}

std::string range_text(const tunable& t) {
    char out[96];
    std::snprintf(out, sizeof out, "%s%g, %g]", t.minimum_exclusive ? "(" : "[", t.minimum, t.maximum);
    return out;
}

}  // namespace

std::pair<std::string, std::string> parse_define(std::string_view text) {
    const std::size_t eq = text.find('=');
    if (eq == std::string_view::npos || eq == 0 || eq + 1 == text.size()) fail(text, "expected NAME=VALUE");
    const std::string name(text.substr(0, eq)), value(text.substr(eq + 1));
    const tunable* found = find_tunable(name);
    if (found == nullptr) {
        std::string known;
        for (const tunable& t : tunables()) known += (known.empty() ? "" : ", ") + std::string(t.name);
        fail(text, "unknown tunable '" + name + "' (known: " + known + ")");
    }
    const tunable& t = *found;
    const bool integral = t.kind != tunable::type::real;
    if (value.find_first_not_of(integral ? "0123456789" : "0123456789.eE+-") != std::string::npos)
        fail(text, name + " takes " + (integral ? "an integer" : "a number") + " in " + range_text(t));
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    const bool below = t.minimum_exclusive ? !(v > t.minimum) : !(v >= t.minimum);
    if (end != value.c_str() + value.size() || errno != 0 || !std::isfinite(v) || below || !(v <= t.maximum))
        fail(text, name + " takes " + (integral ? "an integer" : "a number") + " in " + range_text(t));
    char literal[48];
    switch (t.kind) {
        case tunable::type::real: std::snprintf(literal, sizeof literal, "%.9ef", v); break;
        case tunable::type::integer: std::snprintf(literal, sizeof literal, "%lld", static_cast<long long>(v)); break;
        case tunable::type::unsigned_integer:
            std::snprintf(literal, sizeof literal, "%lluu", static_cast<unsigned long long>(v));
            break;
    }
    return {name, literal};
}

void add_define(std::vector<std::pair<std::string, std::string>>& defines, std::string_view text) {
    std::pair<std::string, std::string> d = parse_define(text);
    defines.erase(std::remove_if(defines.begin(), defines.end(), [&](const auto& e) { return e.first == d.first; }),
                  defines.end());
    defines.push_back(std::move(d));
}

double tunable_value(const define_list& defines, std::string_view name) {
    const tunable* found = find_tunable(name);
    if (found == nullptr) throw tunable_error("tunable_value: '" + std::string(name) + "' is not a tunable");
    for (auto it = defines.rbegin(); it != defines.rend(); ++it)
        if (it->first == name) return std::strtod(it->second.c_str(), nullptr);  // stops at the literal's suffix
    return found->default_value;
}

void check_tunables(const define_list& defines) {
    const double n_min = tunable_value(defines, "EMCV_HISTORY_N_MIN"), n_max = tunable_value(defines, "EMCV_HISTORY_N_MAX");
    const double budget = tunable_value(defines, "EMCV_HISTORY_SPP_BUDGET");
    char text[160];
    if (n_min > n_max) {
        std::snprintf(text, sizeof text, "--define: EMCV_HISTORY_N_MIN (%g) exceeds EMCV_HISTORY_N_MAX (%g)", n_min, n_max);
        throw tunable_error(text);
    }
    const double block = tunable_value(defines, "EMCV_HISTORY_BLOCK");
    if (block != 1.0 && block != 2.0 && block != 4.0) {
        std::snprintf(text, sizeof text, "--define: EMCV_HISTORY_BLOCK (%g) is not 1, 2 or 4 (a divisor of the 8x8 SSS tile)", block);
        throw tunable_error(text);
    }
    if (budget > n_max) {
        std::snprintf(text, sizeof text, "a budget of %g samples per pixel exceeds EMCV_HISTORY_N_MAX (%g)", budget, n_max);
        throw tunable_error(text);
    }
}

void add_sampling_flag(define_list& defines, std::string_view flag, std::string_view value, std::string& previous) {
    const bool budget = flag == "--spp-budget";
    if (!budget && flag != "--target-variance")
        throw tunable_error("add_sampling_flag: '" + std::string(flag) + "' is not a sampling flag");
    if (!previous.empty() && previous != flag)
        throw tunable_error(std::string(flag) + ": cannot be combined with " + previous +
                            " (a run spends a budget or aims at a variance, not both)");
    previous = std::string(flag);
    const std::string name = budget ? "EMCV_HISTORY_SPP_BUDGET" : "EMCV_HISTORY_TARGET";
    try {
        const std::pair<std::string, std::string> d = parse_define(name + "=" + std::string(value));
        if (budget && !(std::strtod(d.second.c_str(), nullptr) > 0.0)) throw tunable_error("zero budget");
    } catch (const tunable_error&) {
        throw tunable_error(std::string(flag) + ": expected a number in " + (budget ? "(0, 1024]" : "(0, 1]") +
                            ", got '" + std::string(value) + "'");
    }
    add_define(defines, name + "=" + std::string(value));
    if (!budget) add_define(defines, "EMCV_HISTORY_SPP_BUDGET=0");
}

std::string sampling_flags_help() {
    return "  --spp-budget B      adaptive methods: spend a mean of B samples per SSS pixel and frame, in\n"
           "                      proportion to each pixel's noise (budget mode; compare with burley-B)\n"
           "  --target-variance V adaptive methods: take N = variance per sample / V samples per pixel (quality\n"
           "                      mode, the default, V = 1e-4); not with --spp-budget\n";
}

std::string sampling_mode::text() const {
    char out[64];
    if (budget)
        std::snprintf(out, sizeof out, "budget %g spp", value);
    else
        std::snprintf(out, sizeof out, "target variance %g", value);
    return out;
}

int learning_updates(double eta, double budget, double n_min) {
    // Each update weighs the history's comoments by 1 - eta, so a pixel whose variance fell to 0 at a change (a
    // light off) keeps (1 - eta)^k of its old variance after k updates, and N proportional to sigma keeps
    // N_0 (1 - eta)^(k / 2) samples: from a mean pixel's B down to N_MIN takes 2 ln(B / N_MIN) / -ln(1 - eta)
    // updates. Never fewer than the memory, 1 / eta.
    const double release = 2.0 * std::log(std::max(budget / n_min, 1.0)) / -std::log1p(-eta);
    return static_cast<int>(std::ceil(std::max(release, 1.0 / eta) - 1e-9));
}

sampling_mode sampling_mode_of(const define_list& defines) {
    const double budget = tunable_value(defines, "EMCV_HISTORY_SPP_BUDGET");
    const bool plan_ahead = tunable_value(defines, "EMCV_HISTORY_PLAN_AHEAD") != 0.0;
    const int period = static_cast<int>(tunable_value(defines, "EMCV_HISTORY_UPDATE_PERIOD"));
    if (budget > 0.0) {
        const double eta = std::min(tunable_value(defines, "EMCV_HISTORY_ETA_MOVING"), tunable_value(defines, "EMCV_HISTORY_ETA_EMCM"));
        return {true, budget, plan_ahead, plan_ahead ? period : 1,
                learning_updates(eta, budget, tunable_value(defines, "EMCV_HISTORY_N_MIN"))};
    }
    return {false, tunable_value(defines, "EMCV_HISTORY_TARGET"), false, 1, 0};
}

}  // namespace emcv::demo
