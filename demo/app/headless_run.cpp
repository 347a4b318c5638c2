// SPDX-License-Identifier: MIT
#include "headless_run.hpp"

#include "render/tunables.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <utility>
#include <stdexcept>
#include <system_error>

#include "gl/image_io.hpp"
#include "heatmap.hpp"
#include "image_metrics.hpp"
#include "progress.hpp"
#include "render_flags.hpp"
#include "render/renderer.hpp"

#include <emcv/port/history.h>

namespace emcv::demo::app {
namespace {

namespace fs = std::filesystem;

image_view view_of(const gl::float_image& image) {
    return {image.width, image.height, image.channels, image.pixels.data()};
}

/// renderer::sss_mask() (one float channel) as the metrics' pixel mask.
pixel_mask mask_of(const gl::float_image& mask) {
    pixel_mask out(static_cast<std::size_t>(mask.width) * static_cast<std::size_t>(mask.height));
    for (std::size_t p = 0; p < out.size(); ++p)
        out[p] = mask.pixels[p * static_cast<std::size_t>(mask.channels)] > 0.5f ? 1 : 0;
    return out;
}

std::string frame_file(int frame, const char* extension, const char* stem = "frame") {
    char name[48];
    std::snprintf(name, sizeof name, "%s-%04d.%s", stem, frame, extension);
    return name;
}

void make_output_directory(const fs::path& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw output_error("cannot create directory '" + dir.string() + "': " + ec.message());
}

/// An image file to write once every method of the frame passed its checks.
struct pending_file {
    fs::path path;
    gl::float_image image;
    std::string description;  ///< the file's ImageDescription ("" for none)
};

void write_frame(const pending_file& file) {
    try {
        gl::write_image(file.path, file.image, file.description);
    } catch (const gl::image_error& e) {
        throw output_error(e.what());
    }
}

/// Metrics of an image holding NaN or Inf would be NaN (and an empty CSV field): stop with the reason instead.
void require_finite(const gl::float_image& image, const char* what, const method& m, int frame) {
    std::size_t bad = 0;
    for (float v : image.pixels) bad += std::isfinite(v) ? 0u : 1u;
    if (bad > 0)
        throw std::runtime_error("frame " + std::to_string(frame) + ", method " + m.name() + ": the " + what +
                                 " image holds " + std::to_string(bad) + " NaN or infinite values");
}

/// Per pixel, the value the adaptive methods track and a quality target bounds the variance of: the gamma-space
/// luminance of albedo * scattered irradiance * exposure (shaders/adaptive/history_io.h, emcv_adaptive_tracked),
/// with the port's own emcv_gamma_luminance. Meaningful at SSS pixels of a method whose SSS passes ran (the
/// reference's held result included: nothing else writes its scattered texture).
std::vector<float> tracked_values(const renderer& r, float exposure) {
    const gl::float_image scattered = r.scattered_irradiance(), albedo = r.surface_albedo();
    std::vector<float> out(static_cast<std::size_t>(scattered.width) * static_cast<std::size_t>(scattered.height));
    for (std::size_t p = 0; p < out.size(); ++p) {
        const glm::vec3 a(albedo.pixels[4 * p], albedo.pixels[4 * p + 1], albedo.pixels[4 * p + 2]);
        const glm::vec3 f(scattered.pixels[4 * p], scattered.pixels[4 * p + 1], scattered.pixels[4 * p + 2]);
        out[p] = emcv::port::emcv_gamma_luminance(a * f * exposure);
    }
    return out;
}

/// One method being rendered: its renderer and the previous frame's display and shown images (temporal error).
struct method_run {
    method m;
    renderer r;
    std::optional<gl::float_image> previous_display;
    std::optional<gl::float_image> previous_shown;  ///< after the temporal resolve (--resolve taa)
};

}  // namespace

std::vector<method> methods_to_render(const std::vector<method>& requested) {
    std::vector<method> out = requested;
    bool has_truth = false;
    for (const method& m : requested) has_truth = has_truth || row_of(m).ground_truth;
    if (!has_truth) out.push_back(ground_truth_method());
    return out;
}

namespace {

/// Fills the rows' times from the frames the renderer has measured (rows are frame-major, method `i` of
/// `count` at frame * count + i). Under GPU timestamps they arrive frames late; `wait` takes the rest.
void fill_times(std::vector<metrics_row>& rows, std::size_t i, std::size_t count, renderer& r, bool wait) {
    for (const frame_times& t : r.take_times(wait)) {
        const std::size_t at = static_cast<std::size_t>(t.frame) * count + i;
        if (at >= rows.size()) throw std::logic_error("headless run: times of a frame not rendered");
        metrics_row& row = rows[at];
        row.sss_ms = t.sss_ms;
        row.frame_ms = t.frame_ms;
        row.passes.clear();
        for (const pass_time& p : t.passes) row.passes.emplace_back(p.name, p.ms);
    }
}

}  // namespace

run_result run_headless(const scene& s, const options& o, int frames, timing clock) {
    const render_options ro = make_render_options(o, clock);

    run_result result;
    std::vector<method_run> runs;
    std::size_t reference_index = 0;
    for (const method& m : methods_to_render(o.methods)) {
        if (row_of(m).ground_truth) reference_index = runs.size();
        runs.push_back({m, renderer(s, m, ro), std::nullopt, std::nullopt});
        result.method_names.push_back(m.name());
    }

    const bool resolves = ro.resolve == resolve_mode::taa;
    progress_bar progress(frames);
    for (int frame = 0; frame < frames; ++frame) {
        // The reference first: every other method of this frame is measured against it.
        method_run& ref = runs[reference_index];
        const frame_stats ref_stats = ref.r.render(frame);
        gl::float_image ref_display = ref.r.display();
        const gl::float_image ref_linear = ref.r.linear();
        require_finite(ref_linear, "linear", ref.m, frame);
        const pixel_mask sss = mask_of(ref.r.sss_mask());
        const std::vector<float> ref_tracked = tracked_values(ref.r, ro.exposure);
        std::optional<gl::float_image>& ref_previous = ref.previous_display;

        // The other methods start one further along each frame, so that no method always renders right
        // after the reference's readback: position in the frame must not show up as a difference in frame_ms
        // between methods (docs/demo.md, no-sss against diffuse). Rows keep the run order.
        std::vector<metrics_row> frame_rows(runs.size());
        std::vector<pending_file> pending;
        for (std::size_t k = 0; k < runs.size(); ++k) {
            const std::size_t i = (k + static_cast<std::size_t>(frame)) % runs.size();
            method_run& run = runs[i];
            const bool is_reference = i == reference_index;
            const frame_stats stats = is_reference ? ref_stats : run.r.render(frame);
            gl::float_image display = is_reference ? ref_display : run.r.display();
            const gl::float_image linear = is_reference ? ref_linear : run.r.linear();
            require_finite(linear, "linear", run.m, frame);

            metrics_row& row = frame_rows[i];
            row.frame = frame;
            row.method = run.m.name();
            row.mean_spp = stats.mean_spp;
            row.max_spp = stats.max_spp;
            row.psnr_db = psnr_db(view_of(display), view_of(ref_display));
            row.psnr_sss_db = psnr_db(view_of(display), view_of(ref_display), &sss);
            row.rel_mse = relative_mse(view_of(linear), view_of(ref_linear));
            if (stats.sss_pixels > 0 && ref_stats.sss_pixels > 0)
                row.tracked_mse = is_reference ? 0.0
                                               : mean_squared_difference(tracked_values(run.r, ro.exposure),
                                                                         ref_tracked, sss);
            if (run.previous_display && ref_previous)
                row.temporal_error = temporal_error(view_of(display), view_of(*run.previous_display),
                                                    view_of(ref_display), view_of(*ref_previous));
            // What the frame shows after its temporal resolve (the reference shows its raw, converged image).
            std::optional<gl::float_image> shown;
            if (resolves && is_reference) {  // it shows its raw image: the raw columns, not recomputed on a copy
                row.psnr_resolved_db = row.psnr_db;
                row.psnr_sss_resolved_db = row.psnr_sss_db;
                row.temporal_error_resolved = row.temporal_error;
            } else if (resolves) {
                shown = run.r.shown();
                row.psnr_resolved_db = psnr_db(view_of(*shown), view_of(ref_display));
                row.psnr_sss_resolved_db = psnr_db(view_of(*shown), view_of(ref_display), &sss);
                if (run.previous_shown && ref_previous)
                    row.temporal_error_resolved = temporal_error(view_of(*shown), view_of(*run.previous_shown),
                                                                 view_of(ref_display), view_of(*ref_previous));
            }

            if (o.out && !o.no_frames) {
                const fs::path dir = *o.out / run.m.name();
                pending.push_back({dir / frame_file(frame, "png"), display, {}});
                if (o.exr) pending.push_back({dir / frame_file(frame, "exr"), linear, {}});
                if (shown) pending.push_back({dir / frame_file(frame, "png", "resolved"), *shown, {}});
                // The heatmaps the method's row asks for, each with its legend: N per pixel, the control-variate
                // coefficient.
                const auto add_heatmap = [&](const char* stem, const gl::float_image& values,
                                             const heatmap_scale& scale) {
                    heatmap_png png = heatmap_with_legend(values, scale);
                    result.heatmap_text_missing = result.heatmap_text_missing || !png.text_drawn;
                    pending.push_back({dir / frame_file(frame, "png", stem), std::move(png.image),
                                       std::move(png.description)});
                };
                if (row_of(run.m).samples_heatmap()) add_heatmap("samples", run.r.sample_counts(), samples_heatmap_scale);
                if (row_of(run.m).alpha_heatmap()) add_heatmap("alpha", run.r.cv_alpha(), alpha_heatmap_scale);
            }
            if (!is_reference) {
                run.previous_display = std::move(display);
                run.previous_shown = std::move(shown);
            }
        }
        if (o.out) {
            // Folders appear with the first frame that is complete: a run that fails earlier leaves nothing.
            if (frame == 0) {
                make_output_directory(*o.out);
                if (!o.no_frames)
                    for (const method_run& run : runs) make_output_directory(*o.out / run.m.name());
            }
            for (const pending_file& file : pending) write_frame(file);
        }
        // The reference's previous image is replaced last: the others compared against the old one above.
        ref.previous_display = std::move(ref_display);
        for (metrics_row& row : frame_rows) result.rows.push_back(std::move(row));
        for (std::size_t i = 0; i < runs.size(); ++i) fill_times(result.rows, i, runs.size(), runs[i].r, false);
        progress.update(frame + 1);
    }
    for (std::size_t i = 0; i < runs.size(); ++i) fill_times(result.rows, i, runs.size(), runs[i].r, true);

    if (o.out) {
        write_file_atomically(*o.out / "metrics.csv", metrics_csv(result.rows));
        write_file_atomically(*o.out / "metrics.json", metrics_json(result.rows, sampling_mode_of(o.defines).text(), timing_name(clock),
                                                                          resolve_label(ro.resolve, ro.jitter)));
    }
    return result;
}

}  // namespace emcv::demo::app
