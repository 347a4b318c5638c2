// SPDX-License-Identifier: MIT
// The per-pixel study of Xie & Olano 2021, section 5: one SSS pixel's adaptive-sampling loop simulated on the CPU with
// the library's own estimators (emcv::emcm, emcv::moving_stats, emcv::cv_coefficient, emcv::sample_count), to
// choose the residual variance that drives the control-variate sample count (docs/renderer.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <emcv/adaptive_sampling.hpp>

namespace emcv::cvstudy {

/// The light's intensity over frames (the scenes light-off, flicker, club, static).
enum class light_curve { switch_off, flicker, sinusoid, constant };

/// How a method turns its history into the next frame's sample count: the library's estimators
/// (emcv::sampling_estimator, one list for the library, Python, the demo and the evaluation), as this study
/// models them per pixel, and for cv the alternative section 5 rejected (method_config::moving_residual):
///   spvg      moving mean/variance (eta 0.2) of f; N = clamp(var / target, 8, 64)
///   cv        EMCM(eta) over (f, G); Var(f - alpha G) = C_ff - C_fG^2 / C_GG
///   cv-notex  alpha = 1: moving variance (eta 0.2) of r = f - G
struct method_config {
    emcv::sampling_estimator kind = emcv::sampling_estimator::spvg;
    float eta = 0.2f;  ///< cv's EMCM weight; the moving-variance weight is always 0.2
    /// -1: the paper's rule on the output's variance: spvg clamp(var / target, 8, 64); the cv family 0
    /// samples on a sub-pixel kernel (here: residual variance exactly 0), else SPVG's clamp. (The renderer
    /// now counts from the per-sample variance instead: docs/renderer.md; this study chose the estimator.)
    /// >= 0: plain clamp(var / target, n_min, 64).
    int n_min = -1;
    /// cv only: the residual's variance from a moving estimate of r = f - alpha G (alpha from the EMCM) instead of
    /// the EMCM's own C_ff - C_fG^2 / C_GG: the variant section 5 compared and the library does not ship.
    bool moving_residual = false;
    std::string name() const;
};

struct study_config {
    std::size_t pixels = 400;
    std::uint64_t seed = 1;
    std::size_t warmup_frames = 60;    ///< frames before the measured window (the switch happens at its end)
    std::size_t window_frames = 30;    ///< measured frames (light-off: the 30 frames from the switch)
    float target = 1.0e-4f;            ///< SPVG's target variance
    int n_max = 64;
    int spvg_n_min = 8;
    float eta_res = 0.2f;              ///< moving-variance weight of SPVG and of the residual (cv_moving, cv_notex)
    bool sub_pixel = false;            ///< kernels under a pixel: the scattered value equals G exactly (no noise)
    /// Which stored state fields are rounded to binary16 after each frame (an RGBA16F history).
    enum class half_fields { none, all, means } half_state = half_fields::none;
};

/// Light intensity of curve c at frame t (warmup frames first; the switch / first burst at frame `warmup`).
float light_at(light_curve c, std::size_t t, std::size_t warmup);

struct method_result {
    std::string method;
    double mean_n = 0.0;        ///< samples per pixel and frame over the window
    double mse = 0.0;           ///< mean squared error of the shown value against the true scattered value
    double psnr_db = 0.0;       ///< 10 log10(1 / mse) (values are display-space luminances in [0, 1])
    double zero_share = 0.0;    ///< share of pixel-frames in the window that took no sample
    std::vector<double> n_per_frame;  ///< mean N over pixels, frame by frame (warmup + window)
};

/// Runs every method of `methods` on the same pixels (same seeds) under curve c.
std::vector<method_result> run_study(light_curve c, const std::vector<method_config>& methods,
                                     const study_config& config);

}  // namespace emcv::cvstudy
