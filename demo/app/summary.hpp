// SPDX-License-Identifier: MIT
// The summary table printed at the end of a run: one line per method, aggregated over its metrics rows.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "metrics_table.hpp"

namespace emcv::demo::app {

struct method_summary {
    std::string method;
    int frames = 0;
    int timed_frames = 0;  ///< frames the times are averaged over
    double sss_ms_mean = 0.0;
    double sss_ms_p95 = 0.0;
    double frame_ms_mean = 0.0;
    double mean_spp = 0.0;  ///< mean over frames of the per-frame mean samples per SSS pixel
    int max_spp = 0;        ///< largest per-pixel count of any frame
    /// Mean over frames of the PSNR in dB, +inf frames (the reference itself) excluded; +inf when every frame
    /// is identical to the reference, empty when no frame defines it.
    std::optional<double> psnr_db;
    std::optional<double> psnr_sss_db;
    /// The same of the shown image after the temporal resolve (psnr_resolved_db); empty under --resolve none.
    std::optional<double> psnr_resolved_db;
};

/// p-th percentile (p in [0, 100]) by linear interpolation between order statistics; 0 for no values.
double percentile(std::vector<double> values, double p);

/// Aggregates rows per method, in the order given. Times (sss_ms, frame_ms) are taken over the frames from
/// `timing_from_frame` on, so that the first frame's one-off costs (shader compilation and first use of each
/// resource on the driver) do not stand in for the steady state; over every frame when none is that late.
/// Sample counts and PSNR are taken over every frame.
std::vector<method_summary> summarize(const std::vector<metrics_row>& rows, const std::vector<std::string>& methods,
                                      int timing_from_frame = 1);

/// The frames a method is compared with its baseline over after a light change (the paper's teaser: the 30
/// frames from the switch).
inline constexpr int switch_window_frames = 30;

/// The summary's closing line: `name` (cv) against `baseline` (spvg, or burley-B at a budget of B) over the
/// `window` frames from `first_change` (the first frame at which a light's intensity changes), cut at the last
/// frame rendered; window 0: every frame from `first_change` on.
/// Sample ratio (mean over frames of mean_spp), SSS-pass-time ratio (mean sss_ms over the window's frames from
/// `timing_from_frame` on, as summarize takes the table's times: frame 0 compiles and first touches every
/// resource, a one-off cost that can outweigh every steady frame; the line says "(from frame F)" where that leaves
/// frames out) and PSNR gap (mean over frames of psnr_db, name minus baseline), then, when the
/// rows have them, the same gap of the resolved images (psnr_resolved_db). Empty when either did not run, or no
/// frame of either lies in the window.
std::optional<std::string> compare_after_change(const std::vector<metrics_row>& rows, int first_change,
                                                const std::string& name, const std::string& baseline,
                                                int window = switch_window_frames, int timing_from_frame = 1);

/// The summary's equal-time line: `name` (cv, spvg, cv-notex) against the burley-N runs of the same rows at
/// `name`'s own SSS time, over the same window as compare_after_change (its times from `timing_from_frame` on).
/// The burley-N runs' mean PSNR is taken as a function of log SSS time, piecewise linear between the runs
/// sorted by time; at `name`'s mean SSS time t, between the runs at t1 <= t <= t2 with PSNRs p1, p2:
/// p(t) = p1 + (p2 - p1) ln(t / t1) / ln(t2 / t1). The line gives both runs, `name`'s time and the PSNR gap
/// (name minus p(t)), then, when every run has it, the same gap of the resolved images. When t is beyond the
/// slowest burley run's time or below the fastest's, the line says so in words ("cv's SSS time is beyond
/// burley-32's ...: no equal-time comparison") instead of extrapolating. Either way the line ends with what
/// `name`'s image is worth in burley samples ("; its image is worth burley-20.2 (resolved burley-18.3)"): the N of
/// equal PSNR on the runs' line through the two that bracket it in PSNR, ln N linear in dB, or "more than
/// burley-64" / "less than burley-4" outside them. That is quality alone, so it holds on any device. Empty when `name` did not run in the
/// window, took no SSS time or has no finite PSNR, or when no burley-N run did.
std::optional<std::string> compare_at_equal_time(const std::vector<metrics_row>& rows, int first_change,
                                                 const std::string& name, int window = switch_window_frames,
                                                 int timing_from_frame = 1);

/// The summary's quality-target line: for each of `names` that has a tracked_mse in the window (see
/// compare_after_change for the window), the mean over frames of tracked_mse, the squared error per SSS pixel
/// of the value the adaptive methods track, in the units of `target_variance` V (the variance a quality target
/// aims each SSS pixel's output at), as a multiple of V, "met" (mean <= V) or "missed", and on how many of the
/// frames the frame's own mean was at most V. Empty when none has one. Throws std::invalid_argument for a V that is not finite and > 0.
std::optional<std::string> compare_with_target(const std::vector<metrics_row>& rows, int first_change,
                                               const std::vector<std::string>& names, double target_variance,
                                               int window = switch_window_frames);

/// The table, then each of `notes` on its own line (the cv vs spvg line after the switch).
std::string format_summary(const std::vector<method_summary>& summaries, const std::vector<std::string>& notes = {});

}  // namespace emcv::demo::app
