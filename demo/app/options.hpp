// SPDX-License-Identifier: MIT
// emcv-demo command line: parsing and validation only (no file system writes, no GL).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "render/renderer.hpp"

namespace emcv::demo::app {

/// Bad command-line input; what() names the flag and the problem. main() prints it on one line, exits 2.
class usage_error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct options {
    std::string scene = "light-off";          ///< --scene FILE|NAME
    std::vector<method> methods;               ///< --method, each once, in order; default all_methods()
    std::optional<int> frames;                 ///< --frames; empty: the scene's own length
    int width = 256;                           ///< --size WxH
    int height = 256;
    std::optional<std::filesystem::path> out;  ///< --out; empty: write nothing but the summary
    std::uint32_t seed = 1;                    ///< --seed
    bool exr = false;                          ///< --exr: also write linear EXR frames
    bool no_frames = false;                    ///< --no-frames: with --out, write the metrics only (benchmarks)
    bool window = false;                       ///< --window: interactive GLFW window
    bool approximate_cdf = false;              ///< --approximate-cdf: SPVG's inverse-CDF fit for burley-N
    timing_request timing = timing_request::automatic;  ///< --timing auto|wall|gpu: the clock of pass times
    resolve_mode resolve = resolve_mode::taa;  ///< --resolve none|taa: the temporal resolve after the composite
    bool jitter = false;                       ///< --jitter: sub-pixel camera jitter for the resolve
    /// --define NAME=VALUE (repeatable): port tunables, validated (render/tunables.hpp), later ones win.
    std::vector<std::pair<std::string, std::string>> defines;
    bool list_methods = false;                 ///< --list-methods: the method table, one name per line
    bool list_scenes = false;
    bool print_passes = false;
    bool help = false;
};

/// Limits on --size (each side, and the pixel count).
inline constexpr int max_side = 8192;
inline constexpr long long max_pixels = 64'000'000;
inline constexpr int max_frames = 100'000;

/// Parses argv[1..]. Throws usage_error on an unknown flag, a missing or malformed value, or a value out of
/// range. Touches nothing outside memory.
options parse_options(const std::vector<std::string>& args);

/// Checks that `dir` is a directory or can be created as one and is writable, leaving nothing behind: the
/// nearest existing ancestor must be a directory in which a probe folder can be created (and is removed).
/// Throws usage_error("--out: ...").
void check_output_directory(const std::filesystem::path& dir);

/// The --help text.
std::string usage_text();

}  // namespace emcv::demo::app
