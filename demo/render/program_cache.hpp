// SPDX-License-Identifier: MIT
// emcv::demo::program_cache — every GLSL program a renderer builds, in one place, keyed by what it is built from:
// its shader files (relative to the shader folder) and the defines it adds to the shared setup's (the tunables).
// A program is compiled on its first request and kept: a method switch, a history made again or a variant asked
// for twice compiles nothing twice, and no program is compiled that no pass asks for.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "gl/program.hpp"
#include "gl/shader_preprocessor.hpp"

namespace emcv::demo {

class program_cache {
public:
    /// Defines as (name, value) pairs, added after the base's in this order.
    using defines = std::vector<std::pair<std::string, std::string>>;

    /// `base`: the include roots and the tunables' defines every program is built with; `shader_dir`: the folder
    /// the files are named relative to.
    program_cache(gl::preprocess_options base, std::filesystem::path shader_dir);

    /// The compute program of `file` ("render/lighting.comp.glsl") with `extra` defines, built on first use.
    /// Throws gl::shader_error naming the file and line where it does not compile (nothing is kept then).
    const gl::program& compute(const std::string& file, const defines& extra = {});
    /// The graphics program of a vertex and a fragment file, as compute.
    const gl::program& graphics(const std::string& vertex, const std::string& fragment, const defines& extra = {});

    /// The options every program starts from (their defines are the tunables').
    const gl::preprocess_options& base() const noexcept { return base_; }
    /// How many programs have been built.
    std::size_t size() const noexcept { return programs_.size(); }

private:
    using key = std::pair<std::vector<std::string>, defines>;
    gl::preprocess_options with(const defines& extra) const;

    gl::preprocess_options base_;
    std::filesystem::path dir_;
    std::map<key, gl::program> programs_;  // node-based: a returned reference stays valid
};

/// A program a pass uses, set by whoever prepares the passes; using an unset one throws, naming the pass.
struct program_ref {
    const gl::program* program = nullptr;
    const char* pass = "";
    void use() const;
};

}  // namespace emcv::demo
