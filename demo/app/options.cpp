// SPDX-License-Identifier: MIT
#include "options.hpp"

#include "cli/command_line.hpp"
#include "render/tunables.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <system_error>

namespace emcv::demo::app {
namespace {

[[noreturn]] void fail(const std::string& flag, const std::string& what, const std::string& value) {
    throw usage_error(flag + ": " + what + ", got '" + value + "'");
}

/// A decimal integer in [lo, hi]; anything else (sign, spaces, trailing text, overflow) is rejected.
long long parse_integer(const std::string& flag, const std::string& value, long long lo, long long hi) {
    if (value.empty() || value.size() > 18 || value.find_first_not_of("0123456789") != std::string::npos)
        fail(flag, "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]", value);
    const long long v = std::strtoll(value.c_str(), nullptr, 10);
    if (v < lo || v > hi)
        fail(flag, "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]", value);
    return v;
}

/// "WxH" with both sides in [1, max_side] and W * H <= max_pixels.
void parse_size(const std::string& flag, const std::string& value, int& width, int& height) {
    const auto x = value.find('x');
    if (x == std::string::npos || value.find('x', x + 1) != std::string::npos)
        fail(flag, "expected WxH, e.g. 256x256", value);
    const std::string w = value.substr(0, x), h = value.substr(x + 1);
    if (w.empty() || h.empty() || w.find_first_not_of("0123456789") != std::string::npos ||
        h.find_first_not_of("0123456789") != std::string::npos || w.size() > 9 || h.size() > 9)
        fail(flag, "expected WxH, e.g. 256x256", value);
    const long long wv = std::stoll(w), hv = std::stoll(h);
    if (wv == 0 || hv == 0) fail(flag, "width and height must be at least 1", value);
    if (wv > max_side || hv > max_side)
        fail(flag, "width and height must be at most " + std::to_string(max_side), value);
    if (wv * hv > max_pixels) fail(flag, "at most " + std::to_string(max_pixels) + " pixels", value);
    width = static_cast<int>(wv);
    height = static_cast<int>(hv);
}

/// One --method item through the renderer's parser (one source of truth for the names).
method parse_method_item(const std::string& item, const std::string& list) {
    const std::optional<method> m = emcv::demo::parse_method(item);
    if (!m) {
        throw usage_error("--method: unknown method '" + item + "' in '" + list + "' (expected " +
                          accepted_method_names() + ", or all)");
    }
    return *m;
}

}  // namespace

std::string usage_text() {
    std::string all;
    for (const method& m : all_methods()) all += (all.empty() ? "" : ",") + m.name();
    return "usage: emcv-demo [options]\n"
           "Real-time subsurface scattering (Xie & Olano 2021): renders a scene with each method, writes frames\n"
           "and per-frame metrics, and prints a summary table.\n"
           "\n"
           "  --scene FILE|NAME   a scene file, or a built-in scene name (default light-off; see --list-scenes)\n"
           "  --method M[,M...]   one or more of these, or all (default all = " + all + "):\n" +
           method_help_lines(22) +
           "  --frames N          frames to render, 1..100000 (default: the scene's length)\n"
           "  --size WxH          image size, each side 1..8192, at most 64000000 pixels (default 256x256)\n"
           "  --out DIR           write frames (PNG), metrics.csv and metrics.json under DIR (default: none)\n"
           "  --seed S            random seed, 0..4294967295 (default 1)\n"
           "  --exr               also write linear HDR frames as EXR\n"
           "  --no-frames         with --out: write metrics.csv/json only, no frames (large benchmark runs)\n"
           "  --approximate-cdf   burley-N draws radii with SPVG's inverse-CDF fit instead of the exact inverse\n"
           + sampling_flags_help() + timing_flag_help() + resolve_flag_help() +
           "  --define NAME=VALUE set a tunable of the port headers for every shader (repeatable; names and\n"
           "                      ranges: docs/renderer.md, Tunables)\n"
           "  --window            show the renderer in a window (keys: see docs/demo.md); --frames ends it\n"
           "  --list-scenes       list the built-in scenes with their descriptions\n"
           "  --print-passes      print the pass list of each frame where it changes, render nothing\n"
           "  --list-methods      print the method table: per line a name, its SSS passes and its help, tab-separated\n"
           "  --help              print this text\n"
           "Bad input exits with status 2 and writes nothing.\n";
}

options parse_options(const std::vector<std::string>& args) {
    options o;
    bool methods_given = false;
    std::string sampling_flag;  // --spp-budget or --target-variance, once seen
    for (std::size_t i = 0; i < args.size(); ++i) {
        cli::flag_argument<usage_error> argument(args, i);
        const std::string& flag = argument.name();
        const std::string& value = argument.inline_value();
        const bool has_inline_value = argument.has_inline_value();
        const auto next_value = [&] { return argument.value(); };
        const auto no_value = [&](bool& target) {
            if (has_inline_value) fail(flag, "takes no value", value);
            target = true;
        };
        if (flag == "--help" || flag == "-h") no_value(o.help);
        else if (flag == "--exr") no_value(o.exr);
        else if (flag == "--no-frames") no_value(o.no_frames);
        else if (flag == "--window") no_value(o.window);
        else if (flag == "--approximate-cdf") no_value(o.approximate_cdf);
        else if (flag == "--jitter") no_value(o.jitter);
        else if (flag == "--list-scenes") no_value(o.list_scenes);
        else if (flag == "--print-passes") no_value(o.print_passes);
        else if (flag == "--list-methods") no_value(o.list_methods);
        else if (flag == "--define") {
            try {
                add_define(o.defines, next_value());
            } catch (const tunable_error& e) {
                throw usage_error(e.what());
            }
        } else if (flag == "--spp-budget" || flag == "--target-variance") {
            try {
                add_sampling_flag(o.defines, flag, next_value(), sampling_flag);
            } catch (const tunable_error& e) {
                throw usage_error(e.what());
            }
        }
        else if (flag == "--timing") {
            try {
                o.timing = parse_timing_flag(next_value());
            } catch (const timing_error& e) {
                throw usage_error(e.what());
            }
        } else if (flag == "--resolve") {
            try {
                o.resolve = parse_resolve_flag(next_value());
            } catch (const resolve_error& e) {
                throw usage_error(e.what());
            }
        } else if (flag == "--scene") {
            o.scene = next_value();
            if (o.scene.empty()) fail(flag, "expected a file or a built-in scene name", o.scene);
        } else if (flag == "--method") {
            const std::string list = next_value();
            // A later --method replaces an earlier one, like every other flag (scripts/quickstart.sh passes
            // --method all and then the user's flags).
            methods_given = true;
            o.methods.clear();
            std::size_t start = 0;
            while (true) {
                const std::size_t comma = list.find(',', start);
                const std::string item = list.substr(start, comma == std::string::npos ? comma : comma - start);
                if (item.empty()) fail(flag, "empty method name in list", list);
                if (item == "all") {
                    for (const method& m : all_methods()) o.methods.push_back(m);
                } else {
                    o.methods.push_back(parse_method_item(item, list));
                }
                if (comma == std::string::npos) break;
                start = comma + 1;
            }
        } else if (flag == "--frames") {
            o.frames = static_cast<int>(parse_integer(flag, next_value(), 1, max_frames));
        } else if (flag == "--size") {
            parse_size(flag, next_value(), o.width, o.height);
        } else if (flag == "--out") {
            const std::string dir = next_value();
            if (dir.empty()) fail(flag, "expected a directory", dir);
            o.out = dir;
        } else if (flag == "--seed") {
            o.seed = static_cast<std::uint32_t>(parse_integer(flag, next_value(), 0, 4294967295ll));
        } else {
            throw usage_error("unknown flag '" + args[i] + "' (see --help)");
        }
    }
    if (!methods_given) o.methods = all_methods();
    // One entry per method: "all,diffuse" must not render diffuse twice.
    std::vector<method> unique;
    for (const method& m : o.methods) {
        bool seen = false;
        for (const method& u : unique) seen = seen || u == m;
        if (!seen) unique.push_back(m);
    }
    o.methods = unique;
    if (o.no_frames && !o.out) throw usage_error("--no-frames: needs --out (it only leaves out the frames)");
    if (o.no_frames && o.exr) throw usage_error("--no-frames: cannot be combined with --exr");
    if (o.window && o.out) throw usage_error("--window: cannot be combined with --out (the window writes nothing)");
    try {
        check_jitter_flag(o.jitter, o.resolve);
    } catch (const resolve_error& e) {
        throw usage_error(e.what());
    }
    try {
        check_tunables(o.defines);
    } catch (const tunable_error& e) {
        throw usage_error(e.what());
    }
    return o;
}

void check_output_directory(const std::filesystem::path& dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path absolute = fs::absolute(dir, ec);
    if (ec) throw usage_error("--out: cannot resolve '" + dir.string() + "': " + ec.message());
    fs::path probe = absolute;
    // Walk up to the nearest existing ancestor: it must be a directory we may create entries in.
    while (!fs::exists(fs::symlink_status(probe, ec)) && probe.has_parent_path() && probe != probe.parent_path())
        probe = probe.parent_path();
    if (!fs::is_directory(probe, ec)) {
        const std::string what = probe == absolute ? "exists and is not a directory"
                                                   : "cannot be created: '" + probe.string() + "' is not a directory";
        throw usage_error("--out: '" + dir.string() + "' " + what);
    }
    // access(2) says yes to root everywhere but on read-only mounts, and procfs or sysfs refuse creation
    // anyway: create and remove a probe folder where --out's first new folder would go. Nothing stays behind.
    const fs::path trial = probe / (".emcv-demo-probe-" + std::to_string(::getpid()));
    if (::mkdir(trial.c_str(), 0700) != 0) {
        const std::string reason = std::error_code(errno, std::generic_category()).message();
        throw usage_error("--out: '" + dir.string() + "' is not writable (cannot create entries in '" +
                          probe.string() + "': " + reason + ")");
    }
    ::rmdir(trial.c_str());
}

}  // namespace emcv::demo::app
