// SPDX-License-Identifier: MIT
// The shader and include folders a test reads at run time, resolved by the renderer's own rule
// (gl::shader_source_dir): the environment variable EMCV_SHADER_DIR / EMCV_INCLUDE_DIR when set and non-empty,
// else the source tree the test was built from. A mutation check points them at a modified copy, and then every test that compiles shaders
// runs that copy, not only the renderer: a test reading the source tree would keep passing on the original.
#pragma once

#include <filesystem>
#include <vector>

#include "gl/shader_preprocessor.hpp"

#ifndef EMCV_SOURCE_DIR
#error "tests/support/source_dirs.hpp needs EMCV_SOURCE_DIR, the source tree the test is built from"
#endif

namespace emcv_test {

/// `$environment` when set and non-empty, else `compiled`.
inline std::filesystem::path dir_from_environment(const char* environment, const std::filesystem::path& compiled) {
    return emcv::gl::shader_source_dir({}, environment, compiled);
}

/// The shaders/ folder: $EMCV_SHADER_DIR, else <source>/shaders.
inline std::filesystem::path shader_dir() {
    return dir_from_environment("EMCV_SHADER_DIR", std::filesystem::path(EMCV_SOURCE_DIR) / "shaders");
}

/// The include root holding emcv/port/*.h: $EMCV_INCLUDE_DIR, else <source>/include.
inline std::filesystem::path include_dir() {
    return dir_from_environment("EMCV_INCLUDE_DIR", std::filesystem::path(EMCV_SOURCE_DIR) / "include");
}

/// The preprocessor's include path in the renderer's order: shader folder first, then the include root.
inline std::vector<std::filesystem::path> shader_include_dirs() { return {shader_dir(), include_dir()}; }

}  // namespace emcv_test
