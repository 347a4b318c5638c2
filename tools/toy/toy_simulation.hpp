// SPDX-License-Identifier: MIT
// The toy experiment of the supplementary, section 3 (Xie & Olano 2021, section 3): five control-variate residuals of
// f(y,t) = h(t)/(1+y) with the control g(y,t) = h(t)(1-y), built only from emcv's public estimators.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace emcv::toy {

/// The light intensity h(t): static h1 = 1, dynamic h2 = 1 + 3 sin(t/10).
enum class scenario { static_light, dynamic_light };

/// How frame 1 seeds the coefficient estimators (the paper leaves it open).
enum class first_frame {
    zero_alpha,  ///< frame 1 is shaded with alpha = 0 (no previous frame), then feeds the estimators
    primed,      ///< frame 1 feeds the estimators first, so its own residual already uses alpha_1
};

/// Which alpha* the ground-truth residual uses.
enum class gt_alpha_source {
    paper,     ///< the paper's large-sample values: static 0.477, dynamic 1.388
    analytic,  ///< (1.5 ln 2 - 1) / (1/12) = 0.4767 and 2 ln 2 = 1.3863
};

/// The table's six residuals, in the paper's column order.
enum residual_index : std::size_t { res_f, res_sf, res_sf_ema, res_emcm, res_emcm_hat, res_gt, residual_count };

/// Names used as JSON keys and CSV column suffixes.
inline constexpr std::array<const char*, residual_count> residual_keys = {"f", "SF", "SF_EMA", "EMCM", "EMCM_hat",
                                                                          "GT"};

/// The paper's single-run Table 1 values.
inline constexpr std::array<double, residual_count> paper_static = {0.0325, 0.0160, 0.0058, 0.0070, 0.0324, 0.0055};
inline constexpr std::array<double, residual_count> paper_dynamic = {0.5585, 0.3797, 0.3742, 0.1295, 0.0732, 0.1243};

/// alpha* in closed form: static Cov(F,G)/Var(G) = (1.5 ln 2 - 1)/(1/12); in-frame constant E(F)/E(G) = 2 ln 2.
double analytic_alpha_static();
double analytic_alpha_dynamic();

struct toy_config {
    std::size_t frames = 100;        ///< frames per run
    std::size_t spp = 16;            ///< correlated samples per frame (the same y feeds f and g)
    std::size_t window_first = 25;   ///< Table 1 averages ReMSE over frames window_first..frames (1-based)
    double eta_cov = 0.05;           ///< EMCM weight over frames (supp. Eq. 21)
    double eta_res = 0.2;            ///< weight of each residual's exponential moving variance
    double eta_sf_ema = 0.05;        ///< EMA weight that smooths alpha_SF in Res_SF+EMA (open in the paper)
    int t0 = 0;                      ///< time t of frame 1 in h2(t) = 1 + 3 sin(t/10) (open in the paper)
    first_frame first = first_frame::primed;  ///< open in the paper, see docs/notebook/2026-12-07-results-toy.md
    gt_alpha_source gt = gt_alpha_source::paper;
};

/// alpha* that Res_GT applies for this scenario under config.gt.
double gt_alpha(scenario s, const toy_config& config);

/// Everything one frame of one run produced (the per-frame CSV row).
struct frame_record {
    std::size_t frame = 0;  ///< 1-based
    double t = 0, h = 0, fbar = 0, gbar = 0, g_expected = 0;
    std::array<double, residual_count> alpha{};     ///< the coefficient applied to this frame (alpha_{t-1})
    std::array<double, residual_count> residual{};  ///< r_t
    std::array<double, residual_count> remse{};     ///< sqrt of the residual's moving variance after frame t
    // supp. Fig. 2, in-frame constant control TG = E(G) T: estimators over the pairs (fbar, G(t)), after frame t.
    double inframe_alpha_emcm = 0, inframe_alpha_ewma = 0;
    double inframe_cov_emcm = 0, inframe_var_emcm = 0, inframe_cov_ewma = 0, inframe_var_ewma = 0;
    double inframe_residual = 0;  ///< fbar - alpha_{t-1} G with that coefficient
};

/// The outcome of one run (one seed, one scenario).
struct run_result {
    std::array<double, residual_count> mean_remse{};  ///< Table 1 cell: ReMSE averaged over the window
    double inframe_alpha_window_mean = 0;             ///< in-frame constant EMCM alpha averaged over the window
    std::vector<frame_record> frames;                 ///< filled only when asked for
};

/// One run. Samples come from std::mt19937_64 seeded with `seed`; both scenarios draw the same y for the
/// same seed (common random numbers).
run_result simulate_run(scenario s, const toy_config& config, std::uint64_t seed, bool record_frames);

struct mean_sd {
    double mean = 0;
    double sd = 0;  ///< sample standard deviation over seeds (n - 1)
};

/// Many seeds of one scenario.
struct scenario_summary {
    std::array<mean_sd, residual_count> cells{};  ///< Table 1 cells over seeds
    mean_sd inframe_alpha{};                      ///< in-frame constant EMCM alpha (window mean) over seeds
    double pooled_alpha = 0;      ///< Cov(f,g)/Var(g) over every sample of every seed (large-sample alpha*)
    std::uint64_t pooled_samples = 0;
    run_result first_run;         ///< the run of the first seed, with its frames recorded
};

/// Runs seeds first_seed, first_seed + 1, ..., first_seed + seeds - 1.
scenario_summary simulate_scenario(scenario s, const toy_config& config, std::uint64_t first_seed,
                                   std::size_t seeds);

}  // namespace emcv::toy
