// SPDX-License-Identifier: MIT
// emcv-demo: renders a scene with each SSS method, writes frames and per-frame metrics, prints a summary.
// Order matters (nothing is written on bad input): parse every flag, load the scene, validate --out, and only
// then create the GL context; outputs are created once the renderers exist.
#include <algorithm>
#include <cmath>
#include <exception>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "gl/context.hpp"
#include "gl/debug.hpp"
#include "headless_run.hpp"
#include "heatmap.hpp"
#include "image/image_file.hpp"
#include "render/tunables.hpp"
#include "light_change.hpp"
#include "listings.hpp"
#include "options.hpp"
#include "scene/load.hpp"
#include "summary.hpp"
#include "window_run.hpp"

namespace {

/// Error messages are one line: multi-line reasons (context creation lists each platform) are joined.
std::string one_line(std::string text) {
    std::string out;
    for (char c : text) {
        if (c == '\n') {
            if (!out.empty() && out.back() != ' ') out += ';';
            continue;
        }
        out += c;
    }
    return out;
}

int fail(int status, const std::string& message) {
    std::cerr << "emcv-demo: " << one_line(message) << '\n';
    return status;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace emcv::demo;
    using namespace emcv::demo::app;
    options o;
    scene s;
    try {
        o = parse_options(std::vector<std::string>(argv + 1, argv + argc));
        if (o.help) {
            std::cout << usage_text();
            return 0;
        }
        if (o.list_scenes) return list_scenes(std::cout) ? 0 : 1;
        if (o.list_methods) {
            list_methods(std::cout);
            return 0;
        }
        s = load_scene_argument(o.scene);
        if (o.out) check_output_directory(*o.out);
    } catch (const usage_error& e) {
        return fail(2, e.what());
    } catch (const scene_error& e) {
        return fail(2, std::string("--scene: ") + e.what());
    } catch (const std::exception& e) {
        return fail(2, e.what());
    }
    const int frames = o.frames.value_or(std::max(1, s.frames));
    if (o.print_passes) {
        print_passes(std::cout, s, o.methods, frames, o.width, o.height, o.resolve, sampling_mode_of(o.defines));
        return 0;
    }

    try {
        emcv::gl::context_options co;
        if (o.window) {
            co.platforms = {emcv::gl::platform::glfw_window};
            co.window_width = o.width;
            co.window_height = o.height;
        }
        emcv::gl::context context(co);
        emcv::gl::debug_messenger messenger;
        if (o.window) {
            std::cerr << window_key_help() << '\n';
            const int shown = run_window(context, s, o, o.frames);
            std::cout << "window: " << shown << " frames of " << s.name << " on " << context.renderer() << '\n';
        } else {
            // Frames are image files: refuse before rendering or creating anything when they cannot be written.
            if (o.out && !o.no_frames) emcv::image::require_image_files();
            const timing clock = resolve_timing(o.timing, context.renderer());
            const run_result result = run_headless(s, o, frames, clock);
            std::vector<std::string> notes;
            const sampling_mode mode = sampling_mode_of(o.defines);
            const std::string cv = method{method::kind::cv}.name(), spvg = method{method::kind::spvg}.name();
            // Under a budget B the adaptive methods are compared at equal cost with burley-B; under a quality
            // target, cv with spvg (the paper's teaser).
            const std::string baseline =
                mode.budget && mode.value == std::floor(mode.value)
                    ? method{method::kind::burley, static_cast<int>(mode.value)}.name()
                    : spvg;
            // The windows the comparisons are taken over: the 30 frames from the first light change, and under a
            // budget every frame too ({first frame, frames; 0: to the end}).
            const std::optional<int> change = first_light_change(s, frames);
            std::vector<std::pair<int, int>> windows;
            if (change) windows.emplace_back(*change, switch_window_frames);
            if (mode.budget) windows.emplace_back(0, 0);
            const auto add = [&notes](std::optional<std::string> line) {
                if (line) notes.push_back(std::move(*line));
            };
            for (const auto& [first, length] : windows) add(compare_after_change(result.rows, first, cv, baseline, length));
            // Each adaptive method against burley-N at its own SSS time: equal samples is not equal cost where a
            // method's per-pixel work does not scale with its samples.
            const std::vector<std::string> adaptive = adaptive_method_names();
            for (const auto& [first, length] : windows)
                for (const std::string& name : adaptive) add(compare_at_equal_time(result.rows, first, name, length));
            // Under a quality target each adaptive method against the target itself, over the 30 frames from the
            // change and every frame: a PSNR gap between two methods does not say which one missed its target.
            if (!mode.budget) {
                if (change) add(compare_with_target(result.rows, *change, adaptive, mode.value));
                add(compare_with_target(result.rows, 0, adaptive, mode.value, 0));
            }
            std::cout << "scene " << s.name << ", " << o.width << "x" << o.height << ", " << frames
                      << " frames, seed " << o.seed << ", adaptive sampling: " << mode.text() << ", "
                      << context.renderer() << '\n'
                      << "times: ms per frame (mean, p95) from frame 1 on (frame 0 is warm-up), clock: "
                      << timing_description(clock, context.renderer())
                      << "; spp: samples per SSS pixel; PSNR: dB of the display image against the reference's, mean "
                         "over frames\n"
                      << format_summary(summarize(result.rows, result.method_names), notes);
            if (o.out)
                std::cout << "wrote " << o.out->string()
                          << (o.no_frames ? "/{metrics.csv,metrics.json}\n"
                                          : std::string("/{metrics.csv,metrics.json,<method>/frame-*.png}") +
                                                (o.resolve == resolve_mode::taa
                                                     ? " (resolved-*.png but the reference's; "
                                                     : " (") +
                                                method_names_where(&method_row::samples_heatmap) +
                                                ": samples-*.png, " + heatmap_scale_text(samples_heatmap_scale) +
                                                "; " + method_names_where(&method_row::alpha_heatmap) +
                                                ": alpha-*.png, " +
                                                heatmap_scale_text(alpha_heatmap_scale) + ")\n");
            if (result.heatmap_text_missing)
                std::cerr << "emcv-demo: the heatmaps' legends have no text: font " << heatmap_font
                          << " not found (scripts/install-deps.sh installs fonts-dejavu-core); their colour bars "
                             "and each PNG's ImageDescription still give the scale\n";
        }
        if (messenger.error_count() > 0)
            return fail(1, std::to_string(messenger.error_count()) + " OpenGL errors, the last: " +
                               messenger.last_error());
    } catch (const emcv::gl::context_error& e) {
        // "(no display)": no platform could even open a display; tests skip GPU cases on that phrase.
        return fail(1, std::string("no OpenGL context") + (e.no_display() ? " (no display)" : "") + ": " + e.what());
    } catch (const output_error& e) {
        return fail(1, std::string("--out: ") + e.what());
    } catch (const emcv::image::image_error& e) {
        return fail(1, std::string("--out: ") + e.what());
    } catch (const std::exception& e) {
        return fail(1, e.what());
    }
    return 0;
}
