// SPDX-License-Identifier: MIT
// The method table (method.hpp) and what derives from it: names, parsing, `all`, help lines.
#include "method.hpp"

#include <emcv/adaptive_sampling.hpp>

#include <algorithm>
#include <charconv>
#include <stdexcept>

namespace emcv::demo {

const std::vector<method_row>& method_table() {
    using k = method::kind;
    using e = emcv::sampling_estimator;
    static const std::vector<method_row> rows{
        {k::diffuse, "diffuse", "no scattering: the lit diffuse as it is (the lower bound of cost)", {}, 0,
         sss_passes::none, std::nullopt, {}},
        {k::burley, "burley", "Burley screen-space SSS, a fixed N samples per SSS pixel",
         {"samples per SSS pixel", 1, 1024, {}, 0, true}, 16, sss_passes::burley, std::nullopt, {}},
        {k::burley_sobol, "burley-sobol",
         "burley-N with scrambled Sobol' points instead of rotated R2 ones (stratified at every power of two)",
         {"samples per SSS pixel", 1, 1024, {}, 0, true}, -1, sss_passes::burley, std::nullopt, "EMCV_BURLEY_SOBOL"},
        {k::separable, "separable", "separable SSS (two 1-D passes) with 11, 17 or 25 taps (default 17)",
         {"taps", 11, 25, {11, 17, 25}, default_separable_taps, true}, default_separable_taps,
         sss_passes::separable, std::nullopt, {}},
        {k::reference, "reference", "Burley with 1024 samples per pixel, reused while its inputs hold",
         {"samples per pixel", 1, 1 << 20, {}, default_reference_samples, false}, default_reference_samples,
         sss_passes::burley, std::nullopt, {}, true},
        {k::spvg, "spvg", "adaptive: N from the moving variance of f (SPVG 2020)", {}, 0, sss_passes::none, e::spvg, {}},
        {k::cv, "cv", "adaptive: N from the residual variance of the control variate, EMCM over (f, G)", {}, 0,
         sss_passes::none, e::cv, {}},
        {k::cv_notex, "cv-notex", "adaptive: N from the moving variance of f - G (alpha = 1)", {}, 0,
         sss_passes::none, e::cv_notex, {}},
    };
    return rows;
}

history_layout method_row::history() const {
    if (!estimator) return history_layout::none;
    return *estimator == emcv::sampling_estimator::cv ? history_layout::emcm2 : history_layout::moving_stats;
}

std::vector<std::pair<std::string, std::string>> method_row::shader_defines() const {
    std::vector<std::pair<std::string, std::string>> out;
    if (!sample_define.empty()) out.emplace_back(std::string(sample_define), "1");
    if (estimator) out.emplace_back(std::string(adaptive_define()), "1");
    return out;
}

std::string_view method_row::adaptive_define() const {
    if (!estimator) return {};
    switch (*estimator) {
        case emcv::sampling_estimator::spvg: return "EMCV_ADAPTIVE_SPVG";
        case emcv::sampling_estimator::cv: return "EMCV_ADAPTIVE_CV";
        case emcv::sampling_estimator::cv_notex: return "EMCV_ADAPTIVE_NOTEX";
    }
    throw std::logic_error("method table: an estimator without a shader define");
}

const method_row& row_of(method::kind type) {
    for (const method_row& r : method_table())
        if (r.type == type) return r;
    throw std::logic_error("method table: no row for a method kind");
}

std::string method::name() const {
    const method_row& r = row_of(type);
    const bool bare = r.parameter.meaning.empty() ||
                      (r.parameter.default_value != 0 && samples == r.parameter.default_value && !r.parameter.on_command_line);
    if (bare) return std::string(r.name);
    return std::string(r.name) + "-" + std::to_string(samples);
}

namespace {

/// The integer after `prefix` + '-' when the whole of `text` is that prefix, a dash and digits.
std::optional<int> suffix_number(std::string_view text, std::string_view prefix) {
    if (text.size() <= prefix.size() + 1 || text.substr(0, prefix.size()) != prefix || text[prefix.size()] != '-')
        return std::nullopt;
    const std::string_view digits = text.substr(prefix.size() + 1);
    int value = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (error != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
    return value;
}

bool parameter_accepts(const method_parameter& p, int value) {
    if (!p.allowed.empty()) return std::find(p.allowed.begin(), p.allowed.end(), value) != p.allowed.end();
    return value >= p.minimum && value <= p.maximum;
}

/// "burley-N (N = 1..1024)", "separable[-11|-17|-25]", "cv".
std::string spelled(const method_row& r) {
    std::string out(r.name);
    const method_parameter& p = r.parameter;
    if (p.meaning.empty() || !p.on_command_line) return out;
    if (!p.allowed.empty()) {
        std::string list;
        for (int v : p.allowed) list += (list.empty() ? "-" : "|-") + std::to_string(v);
        return p.default_value != 0 ? out + "[" + list + "]" : out + list;
    }
    return out + "-N (N = " + std::to_string(p.minimum) + ".." + std::to_string(p.maximum) + ")";
}

}  // namespace

std::optional<method> parse_method(std::string_view text) {
    for (const method_row& r : method_table()) {
        const method_parameter& p = r.parameter;
        if (text == r.name) {
            if (p.meaning.empty()) return method{r.type, 0};
            if (p.default_value != 0) return method{r.type, p.default_value};
            return std::nullopt;
        }
        if (p.meaning.empty() || !p.on_command_line) continue;
        if (const std::optional<int> n = suffix_number(text, r.name)) {
            if (parameter_accepts(p, *n)) return method{r.type, *n};
            return std::nullopt;
        }
    }
    return std::nullopt;
}

method make_reference(int samples) { return method{method::kind::reference, samples}; }

method ground_truth_method() {
    for (const method_row& r : method_table())
        if (r.ground_truth) return method{r.type, r.parameter.default_value};
    throw std::logic_error("method table: no row is the ground truth");
}

std::vector<method> all_methods() {
    std::vector<method> out;
    for (const method_row& r : method_table())
        if (r.in_all >= 0) out.push_back(method{r.type, r.in_all});
    return out;
}

std::string accepted_method_names() {
    std::string out;
    for (const method_row& r : method_table()) out += (out.empty() ? "" : ", ") + spelled(r);
    return out;
}

std::vector<std::string> adaptive_method_names() {
    std::vector<std::string> out;
    for (const method_row& r : method_table())
        if (r.estimator) out.emplace_back(r.name);
    return out;
}

std::string method_names_where(bool (method_row::*flag)() const) {
    std::string out;
    for (const method_row& r : method_table())
        if ((r.*flag)()) out += (out.empty() ? "" : ", ") + std::string(r.name);
    return out;
}

std::string method_help_lines(std::size_t indent) {
    std::size_t width = 0;
    for (const method_row& r : method_table()) width = std::max(width, spelled(r).size());
    std::string out;
    for (const method_row& r : method_table()) {
        const std::string name = spelled(r);
        out += std::string(indent, ' ') + name + std::string(width + 2 - name.size(), ' ') + std::string(r.help) + "\n";
    }
    return out;
}

}  // namespace emcv::demo
