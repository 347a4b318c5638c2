// SPDX-License-Identifier: MIT
// Runs a shell command from a test and captures its exit code, standard output and standard error.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace emcv_test {

struct command_result {
    int exit_code = -1;  ///< the command's exit status, -1 when it did not exit normally
    std::string out;     ///< standard output
    std::string err;     ///< standard error
    std::string output() const { return out + err; }
};

inline std::string read_file(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// Runs `command` through /bin/sh with stdout and stderr redirected to scratch files.
inline command_result run_command(const std::string& command) {
    namespace fs = std::filesystem;
    static int serial = 0;
    const fs::path base = fs::temp_directory_path() /
                          ("emcv-test-" + std::to_string(::getpid()) + "-" + std::to_string(serial++));
    const fs::path out = base.string() + ".out", err = base.string() + ".err";
    const std::string full = "(" + command + ") >'" + out.string() + "' 2>'" + err.string() + "'";
    const int raw = std::system(full.c_str());
    command_result r;
    r.exit_code = raw != -1 && WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = read_file(out);
    r.err = read_file(err);
    std::error_code ignored;
    fs::remove(out, ignored);
    fs::remove(err, ignored);
    return r;
}

/// True when a tool could not get an OpenGL context because there is no display at all (no EGL device, no X
/// server; gl::context says "(no display)"): the GPU-dependent cases skip then, as tests/gpu does.
inline bool no_display(const command_result& r) {
    return r.exit_code == 1 && r.err.find("(no display)") != std::string::npos;
}

/// The fields of one CSV line (no quoting); a trailing separator gives a trailing empty field.
inline std::vector<std::string> split_fields(const std::string& line, char separator = ',') {
    std::vector<std::string> fields;
    std::stringstream in(line);
    for (std::string f; std::getline(in, f, separator);) fields.push_back(f);
    if (!line.empty() && line.back() == separator) fields.emplace_back();
    return fields;
}

}  // namespace emcv_test
