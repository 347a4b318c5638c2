// SPDX-License-Identifier: MIT
// emcv-eval: the renderer's cost per frame (eval_options.hpp for the flags). Methods are rendered side by side
// (each frame: every method in turn) so that the machine's load, shared with other work, hits them alike.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <system_error>
#include <vector>

#include "eval_options.hpp"
#include "render/tunables.hpp"
#include "gl/context.hpp"
#include "gl/debug.hpp"
#include "render/renderer.hpp"
#include "render_flags.hpp"
#include "scene/load.hpp"

namespace fs = std::filesystem;
using namespace emcv;

namespace {

/// One channel of a GL image (bottom row first) as CSV, top row first; written through a temporary name.
void write_csv(const fs::path& file, const gl::float_image& img) {
    const fs::path tmp = file.string() + ".tmp";
    {
        std::ofstream out(tmp);
        for (int y = img.height - 1; y >= 0; --y) {
            for (int x = 0; x < img.width; ++x) {
                const std::size_t at = (static_cast<std::size_t>(y) * static_cast<std::size_t>(img.width) +
                                        static_cast<std::size_t>(x)) * static_cast<std::size_t>(img.channels);
                out << (x ? "," : "") << img.pixels[at];
            }
            out << '\n';
        }
        if (!out) throw std::runtime_error(file.string() + ": cannot write");
    }
    fs::rename(tmp, file);
}

/// One printed row before its times are known.
struct eval_row {
    std::string method;
    int frame = 0;
    double sss_ms = 0.0, frame_ms = 0.0, mean_spp = 0.0;
    int max_spp = 0;
    std::size_t sss_pixels = 0;
    std::string lights;
    std::string resolve = "none";  ///< the temporal resolve this method's frame ran (the reference never does)
    bool timed = false;
};

int run(const eval::options& o) {
    demo::scene s = demo::load_scene_argument(o.scene);
    for (demo::material& m : s.materials)
        if (m.scatters()) m.mean_free_path_mm *= o.sss_scale;
    const int frames = o.frames > 0 ? o.frames : std::max(1, s.frames);
    if (!o.heatmap_dir.empty()) fs::create_directories(o.heatmap_dir);

    gl::context context;
    gl::debug_messenger messenger;
    const demo::timing clock = demo::resolve_timing(o.timing, context.renderer());
    const demo::render_options ro = demo::app::make_render_options(o, clock);
    std::vector<demo::renderer> renderers;
    for (const demo::method& m : o.methods) renderers.emplace_back(s, m, ro);

    // The adaptive methods' sampling mode and the clock, one value per run, repeated on each row so that rows
    // stand alone.
    const std::string sampling = demo::sampling_mode_of(o.defines).text();
    std::printf("scene,width,height,sss_scale,method,frame,sss_ms,frame_ms,mean_spp,max_spp,sss_pixels,lights,sampling,"
                "timing,resolve\n");
    // A row waits for its frame's times (under GPU timestamps they arrive frames late); rows are printed
    // frame-major as soon as every method's row of a frame is complete.
    std::vector<eval_row> rows;
    std::size_t printed = 0;
    const auto take_times = [&](bool wait) {
        for (std::size_t i = 0; i < renderers.size(); ++i)
            for (const demo::frame_times& t : renderers[i].take_times(wait)) {
                eval_row& row = rows.at(static_cast<std::size_t>(t.frame) * renderers.size() + i);
                row.sss_ms = t.sss_ms;
                row.frame_ms = t.frame_ms;
                row.timed = true;
            }
        for (; printed < rows.size() && rows[printed].timed; ++printed) {
            const eval_row& r = rows[printed];
            std::printf("%s,%d,%d,%g,%s,%d,%.4f,%.4f,%.3f,%d,%zu,%s,%s,%s,%s\n", s.name.c_str(), o.width, o.height,
                        static_cast<double>(o.sss_scale), r.method.c_str(), r.frame, r.sss_ms, r.frame_ms, r.mean_spp,
                        r.max_spp, r.sss_pixels, r.lights.c_str(), sampling.c_str(), demo::timing_name(clock),
                        r.resolve.c_str());
        }
    };
    for (int frame = 0; frame < frames; ++frame) {
        const bool dump = std::find(o.heatmap_frames.begin(), o.heatmap_frames.end(), frame) != o.heatmap_frames.end();
        std::string lights;  // "name=intensity;...": the scene's curves at this frame (scene::curve::at)
        for (const demo::light& l : s.lights)
            lights += (lights.empty() ? "" : ";") + l.name + "=" + std::to_string(l.intensity.at(frame));
        for (std::size_t i = 0; i < renderers.size(); ++i) {
            const demo::frame_stats& st = renderers[i].render(frame);
            const std::string name = o.methods[i].name();
            const bool resolved = o.resolve == demo::resolve_mode::taa && demo::row_of(o.methods[i]).resolves();
            rows.push_back({name, frame, 0.0, 0.0, st.mean_spp, st.max_spp, st.sss_pixels, lights,
                            demo::resolve_label(resolved ? o.resolve : demo::resolve_mode::none, o.jitter), false});
            if (dump) {
                const std::string stem = name + ".f" + std::to_string(frame);
                write_csv(o.heatmap_dir / (stem + ".samples.csv"), renderers[i].sample_counts());
                if (demo::row_of(o.methods[i]).alpha_heatmap())
                    write_csv(o.heatmap_dir / (stem + ".alpha.csv"), renderers[i].cv_alpha());
                write_csv(o.heatmap_dir / (stem + ".mask.csv"), renderers[i].sss_mask());
            }
        }
        take_times(false);
    }
    take_times(true);
    std::fflush(stdout);
    if (messenger.error_count() > 0) {
        std::fprintf(stderr, "emcv-eval: %llu OpenGL errors, the last: %s\n",
                     static_cast<unsigned long long>(messenger.error_count()), messenger.last_error().c_str());
        return 1;
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    eval::options o;
    try {
        o = eval::parse_options(std::vector<std::string>(argv + 1, argv + argc));
        if (o.help) {
            std::cout << eval::usage_text();
            return 0;
        }
    } catch (const eval::usage_error& e) {
        std::fprintf(stderr, "emcv-eval: %s\n", e.what());
        return 2;
    }
    try {
        return run(o);
    } catch (const demo::scene_error& e) {
        std::fprintf(stderr, "emcv-eval: --scene: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "emcv-eval: %s\n", e.what());
        return 1;
    }
}
