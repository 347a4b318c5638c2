// SPDX-License-Identifier: MIT
#include "toy_simulation.hpp"

#include <cmath>
#include <random>

#include <emcv/emcv.hpp>

namespace emcv::toy {
namespace {

double light_intensity(scenario s, double t) {
    return s == scenario::static_light ? 1.0 : 1.0 + 3.0 * std::sin(t / 10.0);  // h1, h2
}

// Table 1 policies, in residual_index order (Res_GT has a fixed alpha and no estimator).
constexpr std::array<residual_policy, res_gt> table_policies = {
    residual_policy::none, residual_policy::single_frame, residual_policy::single_frame_ema,
    residual_policy::emcm_sampled, residual_policy::emcm_constant};

run_result run_one(scenario s, const toy_config& config, std::uint64_t seed, bool record_frames,
                   running_covariance<double, 2>* pooled) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);

    std::array<control_variate<double>, res_gt> cvs = {
        control_variate<double>(table_policies[0], config.eta_cov, config.eta_sf_ema),
        control_variate<double>(table_policies[1], config.eta_cov, config.eta_sf_ema),
        control_variate<double>(table_policies[2], config.eta_cov, config.eta_sf_ema),
        control_variate<double>(table_policies[3], config.eta_cov, config.eta_sf_ema),
        control_variate<double>(table_policies[4], config.eta_cov, config.eta_sf_ema)};
    const double alpha_gt = gt_alpha(s, config);

    std::array<moving_stats<double>, residual_count> residual_stats = {
        moving_stats<double>(config.eta_res), moving_stats<double>(config.eta_res),
        moving_stats<double>(config.eta_res), moving_stats<double>(config.eta_res),
        moving_stats<double>(config.eta_res), moving_stats<double>(config.eta_res)};

    // supp. Fig. 2: in-frame constant control (TG = E(G) T, Eq. 38), EMCM (Eq. 21) beside EWMA (Eq. 22).
    control_variate<double> inframe(residual_policy::emcm_constant, config.eta_cov);
    ewma_covariance<double, 2> inframe_ewma(config.eta_cov);

    run_result result;
    if (record_frames) result.frames.reserve(config.frames);
    std::array<double, residual_count> remse_sum{};
    double inframe_alpha_sum = 0;
    std::size_t window_frames = 0;

    for (std::size_t frame = 1; frame <= config.frames; ++frame) {
        const double t = static_cast<double>(config.t0) + static_cast<double>(frame - 1);
        const double h = light_intensity(s, t);

        running_covariance<double, 2> in_frame;  // the frame's spp correlated (f, g) pairs
        for (std::size_t i = 0; i < config.spp; ++i) {
            const double y = uniform(rng);
            const std::array<double, 2> fg = {h / (1.0 + y), h * (1.0 - y)};
            in_frame.push(fg);
            if (pooled) pooled->push(fg);
        }
        const double g_expected = 0.5 * h;  // G(t) = integral of g over y
        const cv_frame<double> fr{in_frame.mean(0), in_frame.mean(1), g_expected, in_frame.covariance(0, 1),
                                  in_frame.variance(1)};
        const bool prime = frame == 1 && config.first == first_frame::primed;

        frame_record rec;
        for (std::size_t k = 0; k < res_gt; ++k) {
            if (prime) cvs[k].update(fr);
            rec.alpha[k] = cvs[k].alpha();
            rec.residual[k] = prime ? cvs[k].residual(fr) : cvs[k].push(fr);
        }
        rec.alpha[res_gt] = alpha_gt;
        rec.residual[res_gt] = cv_residual(fr.f, alpha_gt, fr.g);

        const bool in_window = frame >= config.window_first;
        for (std::size_t k = 0; k < residual_count; ++k) {
            residual_stats[k].push(rec.residual[k]);
            rec.remse[k] = std::sqrt(residual_stats[k].variance());
            if (in_window) remse_sum[k] += rec.remse[k];
        }

        // The in-frame constant variant: its EMCM sees (fbar, G) and its residual is fbar - alpha G.
        const cv_frame<double> fr_const{fr.f, g_expected, g_expected, 0.0, 0.0};
        if (prime) inframe.update(fr_const);
        rec.inframe_residual = prime ? inframe.residual(fr_const) : inframe.push(fr_const);
        inframe_ewma.push(std::array<double, 2>{fr.f, g_expected});
        rec.inframe_alpha_emcm = inframe.alpha();
        rec.inframe_alpha_ewma = cv_coefficient(inframe_ewma.covariance(0, 1), inframe_ewma.variance(1));
        if (in_window) inframe_alpha_sum += rec.inframe_alpha_emcm;
        if (in_window) ++window_frames;

        if (record_frames) {
            rec.frame = frame;
            rec.t = t;
            rec.h = h;
            rec.fbar = fr.f;
            rec.gbar = fr.g;
            rec.g_expected = g_expected;
            rec.inframe_cov_emcm = inframe.frame_covariance().covariance(0, 1);
            rec.inframe_var_emcm = inframe.frame_covariance().variance(1);
            rec.inframe_cov_ewma = inframe_ewma.covariance(0, 1);
            rec.inframe_var_ewma = inframe_ewma.variance(1);
            result.frames.push_back(rec);
        }
    }
    const double n = static_cast<double>(window_frames);
    for (std::size_t k = 0; k < residual_count; ++k) result.mean_remse[k] = remse_sum[k] / n;
    result.inframe_alpha_window_mean = inframe_alpha_sum / n;
    return result;
}

mean_sd to_mean_sd(const running_covariance<double, 1>& acc) {
    return {acc.mean(0), std::sqrt(acc.sample_variance(0))};
}

}  // namespace

double analytic_alpha_static() { return (1.5 * std::log(2.0) - 1.0) / (1.0 / 12.0); }
double analytic_alpha_dynamic() { return 2.0 * std::log(2.0); }

double gt_alpha(scenario s, const toy_config& config) {
    if (config.gt == gt_alpha_source::analytic)
        return s == scenario::static_light ? analytic_alpha_static() : analytic_alpha_dynamic();
    return s == scenario::static_light ? 0.477 : 1.388;
}

run_result simulate_run(scenario s, const toy_config& config, std::uint64_t seed, bool record_frames) {
    return run_one(s, config, seed, record_frames, nullptr);
}

scenario_summary simulate_scenario(scenario s, const toy_config& config, std::uint64_t first_seed,
                                   std::size_t seeds) {
    scenario_summary summary;
    std::array<running_covariance<double, 1>, residual_count> cell_acc;
    running_covariance<double, 1> inframe_acc;
    running_covariance<double, 2> pooled;
    for (std::size_t i = 0; i < seeds; ++i) {
        run_result run = run_one(s, config, first_seed + i, i == 0, &pooled);
        for (std::size_t k = 0; k < residual_count; ++k) cell_acc[k].push(run.mean_remse[k]);
        inframe_acc.push(run.inframe_alpha_window_mean);
        if (i == 0) summary.first_run = std::move(run);
    }
    for (std::size_t k = 0; k < residual_count; ++k) summary.cells[k] = to_mean_sd(cell_acc[k]);
    summary.inframe_alpha = to_mean_sd(inframe_acc);
    summary.pooled_alpha = cv_coefficient(pooled.covariance(0, 1), pooled.variance(1));
    summary.pooled_samples = pooled.count();
    return summary;
}

}  // namespace emcv::toy
