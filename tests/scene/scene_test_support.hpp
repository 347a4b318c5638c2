// SPDX-License-Identifier: MIT
// Shared by the scene tests: a fresh temporary folder per test case, and writing files into it.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace emcv::test {

/// A new empty folder under the system temporary folder, removed with everything in it on destruction.
class temp_folder {
public:
    temp_folder();
    ~temp_folder();
    temp_folder(const temp_folder&) = delete;
    temp_folder& operator=(const temp_folder&) = delete;
    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path write(const std::string& name, const std::string& contents) const;
    std::filesystem::path write_json(const std::string& name, const nlohmann::json& value) const;

private:
    std::filesystem::path path_;
};

/// A unit right tetrahedron (volume 1/6), counter-clockwise from outside, as OBJ text.
inline constexpr const char* tetrahedron_obj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

/// The repository root (compile definition).
std::filesystem::path source_dir();

}  // namespace emcv::test
