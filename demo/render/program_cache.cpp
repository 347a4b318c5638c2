// SPDX-License-Identifier: MIT
#include "program_cache.hpp"

#include <stdexcept>

namespace emcv::demo {

program_cache::program_cache(gl::preprocess_options base, std::filesystem::path shader_dir)
    : base_(std::move(base)), dir_(std::move(shader_dir)) {}

gl::preprocess_options program_cache::with(const defines& extra) const {
    gl::preprocess_options options = base_;
    options.defines.insert(options.defines.end(), extra.begin(), extra.end());
    return options;
}

const gl::program& program_cache::compute(const std::string& file, const defines& extra) {
    key k{{file}, extra};
    auto it = programs_.find(k);
    if (it == programs_.end()) it = programs_.emplace(std::move(k), gl::program::compute(dir_ / file, with(extra))).first;
    return it->second;
}

const gl::program& program_cache::graphics(const std::string& vertex, const std::string& fragment,
                                           const defines& extra) {
    key k{{vertex, fragment}, extra};
    auto it = programs_.find(k);
    if (it == programs_.end())
        it = programs_.emplace(std::move(k), gl::program::graphics(dir_ / vertex, dir_ / fragment, with(extra))).first;
    return it->second;
}

void program_ref::use() const {
    if (program == nullptr) throw std::logic_error(std::string("pass ") + pass + ": its program was not prepared");
    program->use();
}

}  // namespace emcv::demo
