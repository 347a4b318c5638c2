// SPDX-License-Identifier: MIT
// What every bad command line of an emcv tool must give: the status, nothing on stdout, and a first stderr
// line "<tool>: ..." that names the problem.
#pragma once

#include <catch2/catch_test_macros.hpp>

#include <string>

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

}  // namespace emcv_cli_test
