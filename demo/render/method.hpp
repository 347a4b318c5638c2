// SPDX-License-Identifier: MIT
// emcv::demo methods: the scattering methods as the command line names them, and the method table, one row
// per method, from which every other part derives what a method does (docs/architecture.md, "Adding a method").
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace emcv {
// The library's estimator (include/emcv/adaptive_sampling.hpp), declared opaquely: a scoped enum with its default
// underlying type is complete here, and this header stays light for the renderer's many sources.
enum class sampling_estimator;
}  // namespace emcv

namespace emcv::demo {

/// A scattering method, as named on the command line (`--method`).
struct method {
    enum class kind { diffuse, burley, burley_sobol, separable, reference, spvg, cv, cv_notex };
    kind type = kind::diffuse;
    /// burley: samples per SSS pixel (1..1024); separable: taps (11, 17 or 25); reference: samples per pixel
    /// (>= 1024 unless a test asks for fewer, see make_reference); 0 for the others.
    int samples = 0;

    /// "diffuse", "burley-16", "separable-17", "reference", "spvg", "cv", "cv-notex".
    std::string name() const;
    bool scatters() const { return type != kind::diffuse; }
    bool operator==(const method& o) const { return type == o.type && samples == o.samples; }
    bool operator!=(const method& o) const { return !(*this == o); }
};

/// The SSS passes a method records between `lighting` and `composite` (pass_list.hpp spells them out).
enum class sss_passes {
    none,       ///< no SSS pass: the composite shows the unscattered diffuse
    burley,     ///< sss-burley with a fixed count per pixel
    separable,  ///< sss-separable-h, sss-separable-v
    adaptive,   ///< sss-adaptive-samples, then sss-burley with N per pixel and the history update
};

/// What an adaptive method keeps per pixel between frames (include/emcv/port/history.h has the layouts).
enum class history_layout {
    none,          ///< no history
    moving_stats,  ///< one RGBA16F texel: moving mean and variance of one scalar (spvg, cv-notex)
    emcm2,         ///< RGBA32F (C_ff, C_fG, C_GG, count) + RG32F (mean_f, mean_G): the EMCM over (f, G) (cv)
};

/// The parameter a method's name carries after a dash ("burley-16", "separable-11").
struct method_parameter {
    std::string_view meaning;  ///< "samples per SSS pixel", "taps"; empty: the method takes none
    int minimum = 0;
    int maximum = 0;
    std::vector<int> allowed;  ///< when not empty, only these values
    int default_value = 0;     ///< the value of the bare name ("separable"); 0: the bare name needs the dash form
    bool on_command_line = true;  ///< false: only the bare name parses (reference; tests set other counts in code)
};

/// One row of the method table. An adaptive method is the one thing its row says once: its estimator (the
/// library's emcv::sampling_estimator), from which its passes, history layout, shader define and heatmaps follow.
struct method_row {
    method::kind type;
    std::string_view name;  ///< the name, or the prefix before "-<parameter>"
    std::string_view help;  ///< one line for --help and --list-methods
    method_parameter parameter;
    int in_all = -1;  ///< the parameter `--method all` renders it with; -1: not part of `all`
    sss_passes fixed_passes = sss_passes::none;  ///< the SSS passes of a method that is not adaptive
    std::optional<emcv::sampling_estimator> estimator;  ///< set: an adaptive method, choosing N with this estimator
    /// The define that selects its sample sequence in the burley pass's taps (render/burley_taps.h); empty: R2
    std::string_view sample_define;
    /// The converged integral every PSNR is measured against (the reference): rendered again only when its inputs
    /// change (holds_result), never jittered or resolved (the truth is the unblurred integral), and added to a run
    /// that does not ask for it (headless_run). One row has it.
    bool ground_truth = false;

    /// The SSS passes it records: sss_passes::adaptive for an adaptive method, else fixed_passes.
    sss_passes passes() const { return estimator ? sss_passes::adaptive : fixed_passes; }
    /// What it keeps per pixel between frames: cv's EMCM, the moving statistics of spvg and cv-notex, or none.
    history_layout history() const;
    /// The define that selects its formulas in the adaptive shaders ("EMCV_ADAPTIVE_CV", ...); empty if none.
    std::string_view adaptive_define() const;
    /// The defines its burley program is built with: its sample sequence's and, adaptive, its method's.
    std::vector<std::pair<std::string, std::string>> shader_defines() const;
    /// --out also writes samples-NNNN.png (N per pixel): every adaptive method.
    bool samples_heatmap() const { return estimator.has_value(); }
    /// --out also writes alpha-NNNN.png (the control-variate coefficient): the layout that holds C_fG / C_GG.
    bool alpha_heatmap() const { return history() == history_layout::emcm2; }
    /// Its last result is shown again while its inputs (camera pose, light radiance) hold: the ground truth.
    bool holds_result() const { return ground_truth; }
    /// The temporal resolve and its camera jitter apply to it: every method but the ground truth.
    bool resolves() const { return !ground_truth; }
};

/// Every method, in the order of `--method all` and of the summary.
const std::vector<method_row>& method_table();
/// The row of a method.
const method_row& row_of(method::kind type);
inline const method_row& row_of(const method& m) { return row_of(m.type); }

/// True for the methods that choose N per pixel from a history (spvg, cv, cv-notex).
inline bool is_adaptive(const method& m) { return row_of(m).estimator.has_value(); }

/// True for the methods whose SSS is a Monte Carlo estimate (the burley pass: burley-N, reference and the
/// adaptive methods): their output carries noise, which the burley pass stores beside it for the resolve.
inline bool samples_randomly(const method& m) {
    return row_of(m).passes() == sss_passes::burley || row_of(m).passes() == sss_passes::adaptive;
}

/// Default sample counts.
inline constexpr int default_separable_taps = 17;
inline constexpr int default_reference_samples = 1024;

/// A method from its command-line name ("burley-16", "separable", "cv", ...) through the table; nullopt for
/// anything else.
std::optional<method> parse_method(std::string_view text);

/// Every method of the table that `--method all` renders, with its parameter there.
std::vector<method> all_methods();

/// The reference with an explicit sample count (tests: convergence against a 4x-sample render).
method make_reference(int samples);
/// The ground truth (the row with ground_truth) at its default sample count.
method ground_truth_method();

/// "diffuse, burley-N (N = 1..1024), ...": the accepted names, for error messages.
std::string accepted_method_names();

/// The names of the adaptive methods (rows with an estimator), in table order: spvg, cv, cv-notex.
std::vector<std::string> adaptive_method_names();

/// The names of the rows for which `flag` (a bool member function of method_row) holds, in table order, joined by
/// ", " ("spvg, cv, cv-notex" for &method_row::samples_heatmap): the text that names them in output.
std::string method_names_where(bool (method_row::*flag)() const);

/// One line per row: "  name  help", the text of --help's method list and of --list-methods.
std::string method_help_lines(std::size_t indent);

}  // namespace emcv::demo
