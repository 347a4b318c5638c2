// SPDX-License-Identifier: MIT
#include "tunables.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace emcv::demo {

const std::vector<tunable>& tunables() {
    using t = tunable::type;
    static const std::vector<tunable> all{
        {"EMCV_HISTORY_TARGET", t::real, 0.0, 1.0, true, "target variance of the gamma-space luminance"},
        {"EMCV_HISTORY_N_MAX", t::integer, 1, 1024, false, "most samples per pixel and frame"},
        {"EMCV_HISTORY_SPVG_N_MIN", t::integer, 0, 1024, false, "spvg's fewest samples per SSS pixel"},
        {"EMCV_HISTORY_RESIDUAL_N_MIN", t::integer, 0, 1024, false, "cv's and cv-notex's fewest samples"},
        {"EMCV_HISTORY_ETA_MOVING", t::real, 0.0, 1.0, true, "moving mean/variance weight (spvg, cv-notex)"},
        {"EMCV_HISTORY_ETA_EMCM", t::real, 0.0, 1.0, true, "EMCM weight (cv)"},
        {"EMCV_HISTORY_MAX_COUNT", t::unsigned_integer, 2, 2048, false, "saturating frame count of a texel"},
        {"EMCV_HISTORY_FOOTPRINT_RADIUS_PER_D", t::real, 0.0, 100.0, true, "kernel radius per shape distance"},
        {"EMCV_HISTORY_CV_SETTLE_N", t::integer, 0, 1024, false, "cv's floor while it settles after a change"},
    };
    return all;
}

namespace {

[[noreturn]] void fail(std::string_view text, const std::string& why) {
    throw tunable_error("--define: " + why + ", got '" + std::string(text) + "'");
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
    const tunable* found = nullptr;
    for (const tunable& t : tunables())
        if (t.name == name) found = &t;
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

}  // namespace emcv::demo
