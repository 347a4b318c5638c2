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

/// parse_define, then into `defines`, replacing an earlier value of the same name (a later --define wins).
void add_define(std::vector<std::pair<std::string, std::string>>& defines, std::string_view text);

}  // namespace emcv::demo
