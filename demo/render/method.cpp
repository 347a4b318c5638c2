// SPDX-License-Identifier: MIT
// Method names on the command line <-> emcv::demo::method.
#include "renderer.hpp"

#include <charconv>

namespace emcv::demo {

std::string method::name() const {
    switch (type) {
        case kind::diffuse: return "diffuse";
        case kind::burley: return "burley-" + std::to_string(samples);
        case kind::separable: return "separable-" + std::to_string(samples);
        case kind::reference:
            return samples == default_reference_samples ? "reference" : "reference-" + std::to_string(samples);
        case kind::spvg: return "spvg";
        case kind::cv: return "cv";
        case kind::cv_notex: return "cv-notex";
    }
    return "unknown";
}

namespace {

/// The integer after `prefix` when the whole of `text` is prefix + digits.
std::optional<int> suffix_number(std::string_view text, std::string_view prefix) {
    if (text.size() <= prefix.size() || text.substr(0, prefix.size()) != prefix) return std::nullopt;
    const std::string_view digits = text.substr(prefix.size());
    int value = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (error != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
    return value;
}

}  // namespace

std::optional<method> parse_method(std::string_view text) {
    if (text == "diffuse") return method{method::kind::diffuse, 0};
    if (text == "reference") return make_reference(default_reference_samples);
    if (text == "spvg") return method{method::kind::spvg, 0};
    if (text == "cv") return method{method::kind::cv, 0};
    if (text == "cv-notex") return method{method::kind::cv_notex, 0};
    if (text == "separable") return method{method::kind::separable, default_separable_taps};
    if (const auto taps = suffix_number(text, "separable-")) {
        if (*taps == 11 || *taps == 17 || *taps == 25) return method{method::kind::separable, *taps};
        return std::nullopt;
    }
    if (const auto n = suffix_number(text, "burley-")) {
        if (*n >= 1 && *n <= 1024) return method{method::kind::burley, *n};
        return std::nullopt;
    }
    return std::nullopt;
}

method make_reference(int samples) { return method{method::kind::reference, samples}; }

std::vector<method> all_methods() {
    return {method{method::kind::diffuse, 0}, method{method::kind::burley, 16},
            method{method::kind::separable, default_separable_taps}, make_reference(default_reference_samples),
            method{method::kind::spvg, 0}, method{method::kind::cv, 0}, method{method::kind::cv_notex, 0}};
}

}  // namespace emcv::demo
