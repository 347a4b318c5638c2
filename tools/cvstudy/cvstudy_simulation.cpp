// SPDX-License-Identifier: MIT
#include <algorithm>
#include "cvstudy_simulation.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include <emcv/control_variate.hpp>
#include <emcv/emcm.hpp>
#include <emcv/moving_stats.hpp>
#include <emcv/port/port.h>
#include <emcv/sample_count.hpp>
#include <glm/gtc/packing.hpp>

namespace emcv::cvstudy {
namespace {

/// splitmix64: a fixed, portable stream per (seed, pixel) so every method sees the same pixels.
struct rng {
    std::uint64_t state;
    std::uint64_t next() {
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
    /// Box-Muller: a standard normal, written out so the stream does not depend on the standard library.
    double normal() {
        const double u1 = 1.0 - uniform();  // (0, 1]
        const double u2 = uniform();
        return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
    }
};

/// One pixel: unscattered value G0 at light 1, scattered/unscattered ratio k, per-sample noise sigma * L * G0.
struct pixel {
    double g0, k, sigma;
};

pixel draw_pixel(rng& r, bool sub_pixel) {
    pixel p;
    p.g0 = 0.2 + 0.6 * r.uniform();
    p.k = sub_pixel ? 1.0 : 0.8 + 0.2 * r.uniform();
    p.sigma = sub_pixel ? 0.0 : 0.1 + 0.2 * r.uniform();
    return p;
}

/// The per-pixel history of one method. next_count() is N for the coming frame; push() takes that frame's
/// shown value f and its control G.
class history {
public:
    history(const method_config& m, const study_config& c)
        : m_(m), c_(c), fg_(m.eta), res_(c.eta_res) {}

    /// N for the coming frame.
    int next_count() const {
        // A reset history (fewer than two frames) has no variance yet: sample at the maximum, as on failed
        // reprojection, instead of trusting a 0 that n_min = 0 would turn into no samples.
        const std::uint64_t seen = emcm_variance() ? fg_.count() : res_.count();
        if (seen < 2) return c_.n_max;
        const float variance =
            emcm_variance() ? cv_optimal_residual_variance(fg_) : res_.variance();
        if (m_.n_min >= 0) return sample_count(variance, c_.target, m_.n_min, c_.n_max);
        // The paper's rules: the cv family takes 0 samples on a sub-pixel kernel (here the pixels drawn with
        // f = G exactly, the only ones whose residual variance is exactly 0), SPVG's clamp otherwise.
        if (m_.kind != sampling_estimator::spvg && variance == 0.0f) return 0;
        return sample_count(variance, c_.target, c_.spvg_n_min, c_.n_max);
    }

    void push(float f, float g) {
        switch (m_.kind) {
            case sampling_estimator::spvg: res_.push(f); break;
            case sampling_estimator::cv_notex: res_.push(cv_residual(f, 1.0f, g)); break;
            case sampling_estimator::cv:
                if (m_.moving_residual) {
                    // r_t with alpha_{t-1}, then the EMCM advances to alpha_t (Xie & Olano 2021, section 5).
                    const float alpha = cv_coefficient(fg_.covariance(0, 1), fg_.variance(1));
                    res_.push(cv_residual(f, alpha, g));
                }
                fg_.push({f, g});
                break;
        }
        if (c_.half_state != study_config::half_fields::none) store_in_half();
    }

private:
    /// Whether N comes from the EMCM's own residual variance (cv as the library has it).
    bool emcm_variance() const { return m_.kind == sampling_estimator::cv && !m_.moving_residual; }

    /// What an RGBA16F history keeps between frames: every mean and (co)variance rounded to binary16 (the
    /// count is an integer below 2048, exact in half). A state that overflowed half is refused by the
    /// estimators' validating constructor and the pixel restarts, as the shader does (docs/numerics.md 4.2).
    static float half(float x) { return glm::unpackHalf1x16(glm::packHalf1x16(x)); }
    template <class Estimator>
    static void round_state(Estimator& e, float eta, bool covariances) {
        auto s = e.state();
        for (float& v : s.mean) v = half(v);
        if (covariances)
            for (float& v : s.covariance) v = half(v);
        try {
            e = Estimator(eta, s);
        } catch (const std::invalid_argument&) {
            e.reset();
        }
    }
    void store_in_half() {
        const bool covariances = c_.half_state == study_config::half_fields::all;
        if (fg_.count() > 0) round_state(fg_, m_.eta, covariances);
        if (res_.count() > 0) round_state(res_, c_.eta_res, covariances);
    }

    method_config m_;
    study_config c_;
    emcm<float, 2> fg_;
    moving_stats<float> res_;
};

}  // namespace

std::string method_config::name() const {
    std::ostringstream s;
    s << sampling_estimator_name(kind);
    if (kind == sampling_estimator::cv) s << (moving_residual ? "-moving-var" : "-emcm-var") << " eta=" << eta;
    if (n_min >= 0) s << " n_min=" << n_min;
    return s.str();
}

float light_at(light_curve c, std::size_t t, std::size_t warmup) {
    constexpr double pi = EMCV_PI;
    switch (c) {
        case light_curve::constant: return 1.0f;
        case light_curve::switch_off: return t < warmup ? 1.0f : 0.25f;
        case light_curve::sinusoid:  // club lighting: period 24 frames between 0.2 and 1
            return static_cast<float>(0.6 + 0.4 * std::sin(2.0 * pi * static_cast<double>(t) / 24.0));
        case light_curve::flicker: {
            // gunshots: from `warmup` on, a burst every 10 frames, 2 frames at 1 over a base of 0.3
            if (t < warmup) return 0.3f;
            return (t - warmup) % 10 < 2 ? 1.0f : 0.3f;
        }
    }
    return 1.0f;
}

std::vector<method_result> run_study(light_curve curve, const std::vector<method_config>& methods,
                                     const study_config& config) {
    const std::size_t frames = config.warmup_frames + config.window_frames;
    std::vector<method_result> out;
    for (const method_config& m : methods) {
        method_result res;
        res.method = m.name();
        res.n_per_frame.assign(frames, 0.0);
        double n_sum = 0.0, se_sum = 0.0, zeros = 0.0;
        for (std::size_t p = 0; p < config.pixels; ++p) {
            rng r{config.seed * 0x100000001B3ull + p};
            const pixel px = draw_pixel(r, config.sub_pixel);
            history h(m, config);
            for (std::size_t t = 0; t < frames; ++t) {
                const double light = light_at(curve, t, config.warmup_frames);
                const double g = light * px.g0;
                const double f_true = px.k * g;
                const int n = h.next_count();
                // The frame's N-sample mean of Gaussian per-sample noise (std sigma L G0) is exactly Gaussian
                // with std sigma L G0 / sqrt(N) (Eq. 27); N = 0 shows the plain diffuse value G.
                const double z = r.normal();  // drawn every frame so methods share the noise stream
                const double f = n > 0 ? f_true + px.sigma * g * z / std::sqrt(static_cast<double>(n)) : g;
                h.push(static_cast<float>(f), static_cast<float>(g));
                res.n_per_frame[t] += n;
                if (t >= config.warmup_frames) {
                    n_sum += n;
                    se_sum += (f - f_true) * (f - f_true);
                    zeros += n == 0 ? 1.0 : 0.0;
                }
            }
        }
        const double count = static_cast<double>(config.pixels * config.window_frames);
        for (double& v : res.n_per_frame) v /= static_cast<double>(config.pixels);
        res.mean_n = n_sum / count;
        res.mse = se_sum / count;
        res.psnr_db = res.mse > 0.0 ? 10.0 * std::log10(1.0 / res.mse) : std::numeric_limits<double>::infinity();
        res.zero_share = zeros / count;
        out.push_back(std::move(res));
    }
    return out;
}

}  // namespace emcv::cvstudy
