// SPDX-License-Identifier: MIT
// What every bad command line of an emcv tool must give: the status, nothing on stdout, and a first stderr
// line "<tool>: ..." that names the problem.
#pragma once

#include <catch2/catch_test_macros.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../support/run_command.hpp"

namespace emcv_cli_test {

inline std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

/// Runs `command` and checks status, empty stdout and a first stderr line "<tool>: " containing `names`.
inline void expect_error(const std::string& tool, const std::string& command, int status, const std::string& names) {
    const emcv_test::command_result r = emcv_test::run_command(command);
    INFO("command: " << command << "\nstdout: " << r.out << "\nstderr: " << r.err);
    CHECK(r.exit_code == status);
    CHECK(r.out.empty());
    const std::string line = first_line(r.err);
    CHECK(line.rfind(tool + ": ", 0) == 0);
    CHECK(line.find(names) != std::string::npos);
}

/// One bad command line: the arguments after the tool and what the error line must contain.
struct bad_usage {
    std::string args;
    std::string names;
};

/// expect_error for each case, the command being `command_prefix + " " + args`.
inline void expect_errors(const std::string& tool, const std::string& command_prefix,
                          const std::vector<bad_usage>& cases, int status = 2) {
    for (const bad_usage& c : cases) expect_error(tool, command_prefix + " " + c.args, status, c.names);
}

/// An empty scratch folder of the system's temporary folder, "emcv-cli-<name>" (emptied when it exists).
inline std::filesystem::path scratch_dir(const std::string& name) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("emcv-cli-" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

/// How many entries `dir` holds (an output left behind shows up here).
inline std::size_t entries(const std::filesystem::path& dir) {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
    return n;
}

/// A regular file in `dir`: a path below it ("<blocker>/out") cannot be created, even by root.
inline std::filesystem::path make_blocker(const std::filesystem::path& dir) {
    const std::filesystem::path blocker = dir / "a-file";
    std::ofstream(blocker) << "not a directory\n";
    return blocker;
}

/// `path` in single quotes for /bin/sh.
inline std::string quoted(const std::filesystem::path& path) { return "'" + path.string() + "'"; }

}  // namespace emcv_cli_test
