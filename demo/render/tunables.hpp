// SPDX-License-Identifier: MIT
// The port's tunables (the `#ifndef NAME` / `#define NAME value` blocks of include/emcv/port/*.h) as the
// renderer accepts them from `--define NAME=VALUE`: each with its type and range, validated before any shader
// sees it, so that a sweep sets a value instead of editing a copy of the headers.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace emcv::demo {

struct tunable {
    enum class type { real, integer, unsigned_integer };
    std::string_view name;
    type kind;
    double minimum;  ///< inclusive, except for `real` with minimum_exclusive
    double maximum;  ///< inclusive
    bool minimum_exclusive;
    std::string_view meaning;
    double default_value;  ///< the header's own value (read from the header's macro)
};

/// Every tunable of the port headers (a test keeps this list equal to the headers' #ifndef blocks).
const std::vector<tunable>& tunables();

/// A --define argument that names no tunable, is not NAME=VALUE, or has a value of the wrong type or range;
/// what() is one line naming the problem.
class tunable_error : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

/// "NAME=VALUE" -> (NAME, the value as a GLSL literal of the tunable's type: "2.5e-05f", "12", "512u").
/// Throws tunable_error.
std::pair<std::string, std::string> parse_define(std::string_view text);

/// The tunables' values as `--define` collects them: (NAME, GLSL literal), later entries win.
using define_list = std::vector<std::pair<std::string, std::string>>;

/// The value `defines` sets NAME to (its last entry), else the header's default. Throws tunable_error for a
/// name that is not a tunable.
double tunable_value(const define_list& defines, std::string_view name);

/// Throws tunable_error when values that are each in range contradict each other: N_MIN > N_MAX, a budget
/// above N_MAX, or a block size (EMCV_HISTORY_BLOCK) that does not divide the 8x8 tile (3).
void check_tunables(const define_list& defines);

/// How the adaptive methods turn per-sample variance into counts (include/emcv/port/history.h), decided by
/// the tunables alone: EMCV_HISTORY_SPP_BUDGET > 0 is budget mode (value = B, mean samples per SSS pixel),
/// else the quality target (value = EMCV_HISTORY_TARGET, the output variance aimed at).
struct sampling_mode {
    bool budget = false;
    double value = 0.0;
    /// Budget mode and EMCV_HISTORY_PLAN_AHEAD: a frame whose next frame shows its view plans that frame's
    /// counts in its burley pass (frame_planner), and the next frame records no samples pass.
    bool plan_ahead = false;
    /// Budget mode with plan_ahead (EMCV_HISTORY_UPDATE_PERIOD, else 1): while view and lights stay still the
    /// history is updated on one frame in update_period; the frames between reuse that update's plan
    /// (frame_planner).
    int update_period = 1;
    /// Budget mode: the updates a history takes after a change of view or lights before frames may reuse a plan
    /// (learning_updates of the slower of EMCV_HISTORY_ETA_MOVING and EMCV_HISTORY_ETA_EMCM, B and N_MIN).
    int learning_updates = 0;
    /// "budget 8 spp" or "target variance 0.0001": what metrics and summaries print.
    std::string text() const;
};
sampling_mode sampling_mode_of(const define_list& defines);

/// The updates after a change of view or lights before a budget's frames may skip the history's update
/// (docs/renderer.md, "Updating one frame in M"): enough for a pixel whose variance fell to 0 to fall from B
/// samples to N_MIN, ceil(2 ln(B / N_MIN) / -ln(1 - eta)), and at least the memory ceil(1 / eta).
int learning_updates(double eta, double budget, double n_min);

/// `--spp-budget B` (B in (0, 1024]) or `--target-variance V` (V in (0, 1]) as the tunables they set:
/// EMCV_HISTORY_SPP_BUDGET = B, or EMCV_HISTORY_TARGET = V with the budget set to 0. `previous` holds the
/// sampling flag seen before ("" for none) and is updated. Throws tunable_error naming the flag for a bad
/// value, or when both flags are given (one sampling mode per run).
void add_sampling_flag(define_list& defines, std::string_view flag, std::string_view value, std::string& previous);

/// The help lines of those two flags, for the command lines that take them.
std::string sampling_flags_help();

/// parse_define, then into `defines`, replacing an earlier value of the same name (a later --define wins).
void add_define(std::vector<std::pair<std::string, std::string>>& defines, std::string_view text);

}  // namespace emcv::demo
