// SPDX-License-Identifier: MIT
// The temporal resolve after the composite (--resolve on emcv-demo and emcv-eval): what an engine shows is not
// the raw noisy frame but its temporal resolve (docs/frame.md, "Temporal resolve").
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace emcv::demo {

/// - none: the composite's image is what is shown; no resolve pass is recorded.
/// - taa: the `resolve` pass after the composite: reprojection with the motion vectors, variance clipping of
///   the history in YCoCg, an exponential blend (include/emcv/port/resolve.h), reset where the history's
///   surface is not this pixel's. Every method but the reference (the converged image) records it.
enum class resolve_mode { none, taa };

/// "none" or "taa"; anything else is empty.
std::optional<resolve_mode> parse_resolve(std::string_view text);
/// A bad --resolve value; what() names the flag, the accepted values and the value given.
class resolve_error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};
/// parse_resolve for the command lines: throws resolve_error on anything else.
resolve_mode parse_resolve_flag(std::string_view value);
/// "none" or "taa" (metrics.json, emcv-eval's rows, the summary).
const char* resolve_name(resolve_mode r);
/// resolve_name, "taa+jitter" under taa with the camera's jitter (metrics.json's "resolve", emcv-eval's column).
std::string resolve_label(resolve_mode r, bool jitter);
/// The --resolve lines of a --help text (22-column layout), --jitter's included.
std::string resolve_flag_help();
/// --jitter needs the resolve: throws resolve_error naming both flags when `jitter` is set without taa.
void check_jitter_flag(bool jitter, resolve_mode r);

}  // namespace emcv::demo
