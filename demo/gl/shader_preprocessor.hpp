// SPDX-License-Identifier: MIT
// emcv::gl shader preprocessor: resolves #include "..." recursively, hoists #version / #extension, injects
// #define lines and emits `#line <index * 1000000 + n> <index>` with a file table, so compile logs can be rewritten to name
// the included file and line (Mesa rejects file names in #line without ARB include).
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace emcv::gl {

/// A shader source could not be read or preprocessed; what() names the file (and line when known).
class shader_error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct preprocess_options {
    /// Roots searched, in order, after the directory of the including file.
    std::vector<std::filesystem::path> include_dirs;
    /// Injected right after #version (and the hoisted #extension lines) as `#define name value`.
    std::vector<std::pair<std::string, std::string>> defines;
    /// Used when no file declares #version.
    std::string default_version = "#version 450 core";
};

struct preprocessed_source {
    std::string text;                ///< plain GLSL, accepted by Mesa and glslangValidator alike
    std::vector<std::string> files;  ///< source-string index -> path, as used in `#line n index`

    /// Rewrites "0:12(5): error" (Mesa) and "ERROR: 0:12: " (glslang) to "path:12(5): error" / "ERROR: path:12: ".
    std::string rewrite_log(const std::string& log) const;
};

/// A folder shaders or port headers are read from at run time: `option` when not empty, else $`environment`
/// when set and non-empty, else `compiled` (the source tree). The renderer and the GPU tests resolve their
/// folders here, so a mutated copy named by EMCV_SHADER_DIR / EMCV_INCLUDE_DIR is what both compile.
std::filesystem::path shader_source_dir(const std::filesystem::path& option, const char* environment,
                                        const std::filesystem::path& compiled);

/// Preprocesses the file at `path`. Throws shader_error for a missing file, an unresolved include or an
/// include cycle. `#pragma once` and #ifndef include guards are both honoured: a guarded file (its first
/// directive `#ifndef X`, then `#define X`, its last the matching `#endif`) is left out where its macro is
/// certainly defined, that is where its first inclusion lay in the same #if branches (the preprocessor does not
/// evaluate conditions) and nothing #undef'd the macro; elsewhere the GLSL compiler drops it by the guard.
preprocessed_source preprocess_file(const std::filesystem::path& path, const preprocess_options& options);

}  // namespace emcv::gl
