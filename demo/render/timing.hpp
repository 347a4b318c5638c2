// SPDX-License-Identifier: MIT
// Which clock the renderer's pass times use (--timing on emcv-demo and emcv-eval), and how `auto` picks one.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace emcv::demo {

/// The clock of the pass times; both stamp every pass boundary (demo/gl/timestamps.hpp).
/// - gpu: GL_TIMESTAMP queries, read back frames later; nothing waits in the measured path. GPU time.
/// - wall: glFinish and the steady clock at every boundary. On llvmpipe the only correct measure: its timer
///   queries do not cover compute dispatches (measured: 0.00 ms for every compute pass), and there the wall
///   clock measures the work (CPU threads), not GPU time.
enum class timing { wall, gpu };

/// --timing as given: auto picks gpu on a hardware renderer and wall on a software one.
enum class timing_request { automatic, wall, gpu };

/// "auto", "wall" or "gpu"; anything else is empty.
std::optional<timing_request> parse_timing(std::string_view text);
/// A bad --timing value; what() names the flag, the accepted values and the value given.
class timing_error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};
/// parse_timing for the command lines: throws timing_error on anything else.
timing_request parse_timing_flag(std::string_view value);
/// True for Mesa's software rasterizers (llvmpipe, softpipe) and other CPU implementations (SwiftShader),
/// judged from GL_RENDERER.
bool is_software_renderer(std::string_view gl_renderer);
/// The clock a run uses: the request, or for auto the renderer's kind.
timing resolve_timing(timing_request request, std::string_view gl_renderer);
/// "gpu" or "wall" (metrics.json, emcv-eval's rows).
const char* timing_name(timing t);
/// One line for the summary header: which clock, and on a software renderer what it measures.
std::string timing_description(timing t, std::string_view gl_renderer);
/// The --timing lines of a --help text (22-column layout).
std::string timing_flag_help();

}  // namespace emcv::demo
