// SPDX-License-Identifier: MIT
// Runs a shell command from a test and captures its exit code, standard output and standard error.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

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

}  // namespace emcv_test
