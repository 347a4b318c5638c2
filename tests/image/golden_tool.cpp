// SPDX-License-Identifier: MIT
// emcv-golden: renders the golden cases (tests/image/golden/cases.txt) and shows what changed.
//   emcv-golden update [--only TEXT]          render, print per image what changed, replace the goldens
//   emcv-golden render --out DIR [--only TEXT] [--seed S]   render into DIR only (S: another seed, to
//                                             measure how far images move when every sample position does)
//   emcv-golden compare ACTUAL EXPECTED       one idiff-style line (display tolerance; ".spp.png": samples)
// scripts/update-golden.sh builds and runs `update`; docs/results.md explains the tolerances.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>
#include <vector>

#include "gl/context.hpp"
#include "gl/debug.hpp"
#include "golden_cases.hpp"
#include "golden_render.hpp"
#include "image_compare.hpp"

namespace fs = std::filesystem;
using namespace emcv::image;

namespace {

const fs::path golden_dir = fs::path(EMCV_IMAGE_DIR) / "golden";

struct usage_error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

const char* const usage =
    "usage: emcv-golden update [--only TEXT]\n"
    "       emcv-golden render --out DIR [--only TEXT] [--seed S]\n"
    "       emcv-golden compare ACTUAL EXPECTED\n";

bool is_samples_file(const fs::path& p) { return p.filename().string().find(".spp.") != std::string::npos; }

/// "unchanged", "new", or what idiff would say against the current golden.
std::string change(const OIIO::ImageBuf& rendered, const fs::path& golden, const tolerance& t) {
    if (!fs::exists(golden)) return "new";
    try {
        const comparison c = compare(rendered, read(golden), t);
        if (c.max_error == 0.0) return "unchanged";
        return c.summary(t);
    } catch (const compare_error& e) {
        return std::string("replaced (") + e.what() + ")";
    }
}

int render_all(const fs::path& out, const std::string& only, bool show_changes, std::uint32_t seed) {
    std::vector<golden_case> cases;
    for (const golden_case& c : read_cases(golden_dir / "cases.txt"))
        if (only.empty() || c.stem().find(only) != std::string::npos) cases.push_back(c);
    if (cases.empty()) throw usage_error("--only '" + only + "' matches no case of " + (golden_dir / "cases.txt").string());
    // before the GL context and the renders: an output folder that cannot be made fails at once
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec || !fs::is_directory(out))
        throw std::runtime_error("--out '" + out.string() + "': cannot create the folder (" +
                                 (ec ? ec.message() : "not a folder") + ")");
    emcv::gl::context context;
    emcv::gl::debug_messenger messenger;
    for (const golden_case& c : cases) {
        const golden_images images = render_case(c, seed);
        const auto emit = [&](const OIIO::ImageBuf& img, const std::string& file, const tolerance& t) {
            if (show_changes) std::cout << file << ": " << change(img, out / file, t) << '\n';
            write(img, out / file);
        };
        emit(images.display, c.display_file(), display_tolerance());
        if (images.sample_counts) emit(*images.sample_counts, c.samples_file(), samples_tolerance());
    }
    if (messenger.error_count() > 0) {
        std::cerr << "emcv-golden: " << messenger.error_count() << " OpenGL errors, the last: "
                  << messenger.last_error() << '\n';
        return 1;
    }
    std::cout << cases.size() << " cases rendered into " << out.string() << '\n';
    return 0;
}

int run(const std::vector<std::string>& args) {
    if (!args.empty() && (args[0] == "--help" || args[0] == "-h")) {
        std::cout << usage;
        return 0;
    }
    if (args.empty()) throw usage_error("missing command (update, render or compare)");
    const std::string& command = args[0];
    std::string only;
    fs::path out;
    std::uint32_t seed = golden_seed;
    std::vector<std::string> positional;
    for (std::size_t i = 1; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--seed") {
            if (i + 1 >= args.size()) throw usage_error("--seed: missing value");
            const std::string& v = args[++i];
            char* end = nullptr;
            const unsigned long parsed = std::strtoul(v.c_str(), &end, 10);
            if (v.empty() || *end != '\0' || parsed > 0xffffffffUL) throw usage_error("--seed: expected 0..4294967295, got '" + v + "'");
            seed = static_cast<std::uint32_t>(parsed);
        } else if (a == "--only" || a == "--out") {
            if (i + 1 >= args.size() || args[i + 1].empty()) throw usage_error(a + ": missing value");
            if (a == "--only")
                only = args[++i];
            else
                out = args[++i];
        } else if (!a.empty() && a[0] == '-') {
            throw usage_error("unknown option '" + a + "'");
        } else {
            positional.push_back(a);
        }
    }
    if (command == "compare") {
        if (positional.size() != 2) throw usage_error("compare: expected ACTUAL EXPECTED");
        const tolerance t = is_samples_file(positional[1]) ? samples_tolerance() : display_tolerance();
        const comparison c = compare_files(positional[0], positional[1], t);
        std::cout << c.summary(t) << '\n';
        return c.result == verdict::fail ? 1 : 0;
    }
    if (!positional.empty()) throw usage_error(command + ": unexpected argument '" + positional[0] + "'");
    if (command == "update") {
        if (!out.empty()) throw usage_error("update writes into " + golden_dir.string() + "; --out is for render");
        if (seed != golden_seed) throw usage_error("update renders with the golden seed only; --seed is for render");
        return render_all(golden_dir, only, true, seed);
    }
    if (command == "render") {
        if (out.empty()) throw usage_error("render: --out DIR is required");
        return render_all(out, only, false, seed);
    }
    throw usage_error("unknown command '" + command + "' (update, render or compare)");
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(std::vector<std::string>(argv + 1, argv + argc));
    } catch (const usage_error& e) {
        std::cerr << "emcv-golden: " << e.what() << '\n' << usage;
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "emcv-golden: " << e.what() << '\n';
        return 1;
    }
}
