// SPDX-License-Identifier: MIT
// emcv-bench's own check of its command line, before Google Benchmark reads it. Google Benchmark 1.7 exits
// 0 after printing its usage on a bad --benchmark_format value, and writes --benchmark_out in place (a run
// that dies leaves half a file). Here an unknown argument or a bad enumerated value is one line and exit 2,
// and --benchmark_out=<path> is written as <path>.partial, renamed to <path> when the run completes.
#pragma once

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace emcv_bench {

struct command_line {
    std::vector<std::string> args;  ///< what Google Benchmark gets, program name first
    std::string out_path;           ///< --benchmark_out, empty when absent
    std::string partial_path;       ///< where Google Benchmark writes it until the run completes
    std::string error;              ///< the usage error, empty when the command line is good
};

namespace detail {

inline bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

/// The value of --name=value in arg, or nullptr when arg is not that flag.
inline const char* flag_value(const std::string& arg, const std::string& name) {
    const std::string prefix = "--" + name + "=";
    return starts_with(arg, prefix) ? arg.c_str() + prefix.size() : nullptr;
}

}  // namespace detail

/// True when path can be created for writing; the probe leaves no file behind (Google Benchmark creates it).
inline bool can_create(const std::string& path) {
    bool ok = false;
    {
        std::ofstream probe(path);
        ok = static_cast<bool>(probe);
    }
    if (ok) std::remove(path.c_str());
    return ok;
}

inline command_line parse_command_line(int argc, char** argv) {
    command_line c;
    c.args.emplace_back(argc > 0 ? argv[0] : "emcv-bench");
    const std::vector<std::string> formats = {"console", "json", "csv"}, units = {"ns", "us", "ms", "s"};
    auto one_of = [](const std::vector<std::string>& allowed, const std::string& v) {
        return std::find(allowed.begin(), allowed.end(), v) != allowed.end();
    };
    for (int i = 1; i < argc && c.error.empty(); ++i) {
        std::string a = argv[i];
        if (a == "--help") {
            c.args.push_back(a);
        } else if (!detail::starts_with(a, "--benchmark_") && !detail::starts_with(a, "--v=")) {
            c.error = "unknown argument '" + a + "'";
        } else if (const char* f = detail::flag_value(a, "benchmark_format"); f && !one_of(formats, f)) {
            c.error = "--benchmark_format must be console, json or csv, got '" + std::string(f) + "'";
        } else if (const char* o = detail::flag_value(a, "benchmark_out_format"); o && !one_of(formats, o)) {
            c.error = "--benchmark_out_format must be console, json or csv, got '" + std::string(o) + "'";
        } else if (const char* u = detail::flag_value(a, "benchmark_time_unit"); u && !one_of(units, u)) {
            c.error = "--benchmark_time_unit must be ns, us, ms or s, got '" + std::string(u) + "'";
        } else if (const char* out = detail::flag_value(a, "benchmark_out")) {
            c.out_path = out;
            c.partial_path = c.out_path + ".partial";
            if (c.out_path.empty()) c.error = "--benchmark_out needs a file name";
            else if (!can_create(c.partial_path)) c.error = "cannot write --benchmark_out '" + c.out_path + "'";
            c.args.push_back("--benchmark_out=" + c.partial_path);
        } else {
            c.args.push_back(a);
        }
    }
    return c;
}

}  // namespace emcv_bench
