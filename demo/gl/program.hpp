// SPDX-License-Identifier: MIT
// GLSL programs built from files through the shader preprocessor. Compile and link errors throw
// shader_error whose message names the original (included) file and line.
#pragma once

#include <filesystem>

#include "handles.hpp"
#include "shader_preprocessor.hpp"

namespace emcv::gl {

class program {
public:
    /// Compute program from one file. Throws shader_error (missing file, bad include, compile or link error).
    static program compute(const std::filesystem::path& path, const preprocess_options& options);
    /// Compute program from already preprocessed text (the file table is used to rewrite the log).
    static program compute(const preprocessed_source& source);
    /// Vertex + fragment program.
    static program graphics(const std::filesystem::path& vertex, const std::filesystem::path& fragment,
                            const preprocess_options& options);

    /// 0 for a program never built.
    GLuint id() const noexcept { return handle_.id(); }
    /// glUseProgram; throws std::logic_error for a program never built (it would bind no program, and the next
    /// dispatch or draw would fail with a bare GL error).
    void use() const;

private:
    program_handle handle_;
};

/// Compiles one stage; throws shader_error with the rewritten log ("file:line(col): error ...").
shader_handle compile_shader(GLenum stage, const preprocessed_source& source);

}  // namespace emcv::gl
