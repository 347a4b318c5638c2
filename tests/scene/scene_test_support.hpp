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

/// The repository root (compile definition).
std::filesystem::path source_dir();

}  // namespace emcv::test
