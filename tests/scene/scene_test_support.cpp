// SPDX-License-Identifier: MIT
#include "scene_test_support.hpp"

#include <fstream>
#include <random>
#include <stdexcept>

#include <unistd.h>

namespace emcv::test {

temp_folder::temp_folder() {
    static unsigned counter = 0;
    const auto base = std::filesystem::temp_directory_path();
    for (int attempt = 0; attempt < 100; ++attempt) {
        const auto candidate =
            base / ("emcv-scene-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
        if (std::filesystem::create_directory(candidate)) {
            path_ = candidate;
            return;
        }
    }
    throw std::runtime_error("temp_folder: cannot create a folder under " + base.string());
}

temp_folder::~temp_folder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
}

std::filesystem::path temp_folder::write(const std::string& name, const std::string& contents) const {
    const auto p = path_ / name;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream out(p, std::ios::binary);
    out << contents;
    if (!out) throw std::runtime_error("temp_folder: cannot write " + p.string());
    return p;
}

std::filesystem::path temp_folder::write_json(const std::string& name, const nlohmann::json& value) const {
    return write(name, value.dump(2));
}

std::filesystem::path source_dir() { return EMCV_SOURCE_DIR; }

}  // namespace emcv::test
