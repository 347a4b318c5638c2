// SPDX-License-Identifier: MIT
// Fuzz target: the per-frame adaptive-sampling API (include/emcv/adaptive_sampling.hpp) on a small frame. The
// input picks the parameters (estimator, mode, target, budget, n_min, n_max, eta: hard cases, raw bits, any
// int), a frame of 1x1 to 16x16 pixels, then up to 64 operations: plan a frame (plan_frame with fuzzer-chosen
// materials, sub-pixel flags, frame index and seed), push a frame (sampling_update with f and G that are hard
// cases or a noisy G(1 + noise) stream, the planned counts or any ints), overwrite one history field with any
// float, reset one pixel's history.
// Invariants checked (adaptive_sampling.hpp's documentation, docs/integration.md step 2):
//   - check_sampling_params, plan_frame and sampling_update throw std::invalid_argument exactly when the
//     parameters break a documented requirement (computed here independently), or the state type is not the
//     estimator's; a refused call changes no state; no other exception escapes;
//   - plan_frame: a pixel of material 0 gets the code emcv_history_no_samples() and 0 samples; so does a
//     sub-pixel pixel under cv and cv_notex; under a quality target every other count lies in [n_min, n_max];
//     under a budget, in [n_min, n_max] for a pixel with a variance (sigma^2 >= 0, +Inf included) and
//     min(B, n_max) rounded down or up for one without; the other codes are non-negative or
//     emcv_history_no_variance(), never NaN, while every history is one the updates produced; frame_plan's
//     samples is the sum of the counts; lambda is 0 under a quality target, and under a budget the lambda
//     budget_solve gives on the scattering pixels' histogram (twice the same);
//   - budget mode's sum: when lambda lies strictly inside the solve's search range and every histogram
//     pixel's sigma inside the histogram's [2^-24, 2^8), the real shares clamp(lambda sigma_i, n_min, n_max)
//     add up to B (histogram pixels + zero pixels) within the bound tests/policy/test_budget_allocation.cpp
//     derives: 2^-13 of the plan (the bins' sums of sigma) + 2^-15 of it (the fp32 sums over at most 256
//     bins) + for each bin a clamp point falls in, count c (hi / lo - 1); the counts differ from the shares
//     by their stochastic rounding, less than 1 per pixel;
//   - sampling_update: a pixel with taken <= 0 is bit-for-bit unchanged; a value the port refuses (f not
//     finite; G too under cv; f - G under cv_notex) adds 1 to `rejected` and changes nothing else; any other
//     push adds 1 to `count` (after a reseed of an overwritten invalid state: count 1, `reseeded` + 1) and
//     leaves the state valid (finite, variances >= 0: emcv_emcm2_valid / emcv_moving_stats_valid) when it
//     was valid or was reseeded.
#include <emcv/adaptive_sampling.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

#include "fuzz_input.hpp"

namespace {

using emcv_fuzz::input;
using emcv::port::EmcvEmcm2;
using emcv::port::EmcvMovingStats;

/// Any int: small ones (where n_min and n_max live) most of the time, else raw bits.
int any_int(input& in) {
    const std::uint8_t tag = in.byte();
    if (tag % 4 != 0) return static_cast<std::int8_t>(in.byte());
    if (tag % 8 == 4) return static_cast<std::int16_t>(in.bits<std::uint16_t>());
    return static_cast<std::int32_t>(in.bits<std::uint32_t>());
}

/// The documented requirements, written out here (not by calling the library).
bool params_valid(const emcv::sampling_params& p) {
    if (p.n_min < 1 || p.n_min > p.n_max || p.n_max > 1024) return false;
    const float eta = p.eta ? *p.eta : (p.estimator == emcv::sampling_estimator::cv ? EMCV_HISTORY_ETA_EMCM
                                                                                     : EMCV_HISTORY_ETA_MOVING);
    if (!(eta > 0.0f && eta <= 0.5f)) return false;
    if (p.mode == emcv::sampling_mode::quality_target) return std::isfinite(p.target) && p.target > 0.0f;
    return std::isfinite(p.budget) && p.budget > 0.0f && p.budget <= static_cast<float>(p.n_max);
}

bool same_bits(const EmcvEmcm2& a, const EmcvEmcm2& b) {
    return std::memcmp(&a, &b, sizeof a) == 0;  // 2 + 3 floats, 3 uints: no padding
}
bool same_bits(const EmcvMovingStats& a, const EmcvMovingStats& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool valid(const EmcvEmcm2& s) { return emcv::port::emcv_emcm2_valid(s); }
bool valid(const EmcvMovingStats& s) { return emcv::port::emcv_moving_stats_valid(s); }

EmcvEmcm2 init(EmcvEmcm2) { return emcv::port::emcv_emcm2_init(); }
EmcvMovingStats init(EmcvMovingStats) { return emcv::port::emcv_moving_stats_init(); }

/// Overwrites one float field of a state with v (the engine's history buffer can hold anything).
void poke(EmcvEmcm2& s, std::uint8_t which, float v) {
    switch (which % 5) {
        case 0: s.mean.x = v; break;
        case 1: s.mean.y = v; break;
        case 2: s.cov.x = v; break;
        case 3: s.cov.y = v; break;
        default: s.cov.z = v; break;
    }
}
void poke(EmcvMovingStats& s, std::uint8_t which, float v) {
    if (which % 2 == 0) s.mean = v;
    else s.variance = v;
}

/// The value the port tests for finiteness before a push (sampling_update's documentation).
bool refused(const emcv::sampling_params& p, float f, float g) {
    switch (p.estimator) {
        case emcv::sampling_estimator::spvg: return !std::isfinite(f);
        case emcv::sampling_estimator::cv: return !std::isfinite(f) || !std::isfinite(g);
        default: return !std::isfinite(emcv::port::emcv_cv_residual(f, 1.0f, g));
    }
}

template <class State>
struct frame_state {
    std::size_t width = 1, pixels = 1;
    std::vector<State> history;
    std::vector<std::uint32_t> material;
    std::vector<std::uint8_t> sub_pixel;
    bool with_material = false, with_sub_pixel = false;
    std::vector<float> sigma2;
    std::vector<int> counts;
};

/// sum_i clamp(lambda sigma_i, n_min, n_max) against B (H + Z), within the derived bound.
void check_budget_sum(const emcv::sampling_params& p, const std::vector<float>& sigma2, const std::uint32_t* material,
                      float lambda, const emcv::budget_histogram& h, const std::vector<int>& counts) {
    if (!(lambda > emcv::port::emcv_bits_float(emcv::port::emcv_budget_lambda_low_bits() + 1u) &&
          lambda < emcv::port::emcv_bits_float(emcv::port::emcv_budget_lambda_high_bits())))
        return;  // at a bound of the search: the plan is out of reach (every pixel at a clamp, or none to spend on)
    const double low_edge = std::ldexp(1.0, EMCV_BUDGET_SIGMA_LOW_EXPONENT);
    const double high_edge = std::ldexp(1.0, EMCV_BUDGET_SIGMA_LOW_EXPONENT + EMCV_BUDGET_BINS / 8);
    const double n_min = p.n_min, n_max = p.n_max;
    double shares = 0, counted = 0;
    std::uint64_t histogram_pixels = 0;
    for (std::size_t i = 0; i < sigma2.size(); ++i) {
        if (material != nullptr && material[i] == 0u) continue;
        if (!(sigma2[i] >= 0.0f)) continue;  // codes: zero or default pixels, outside the solve
        const double sigma = static_cast<double>(std::sqrt(sigma2[i]));  // as budget_add bins it: the float's sqrt
        if (!(sigma >= low_edge && sigma < high_edge)) return;  // binned at an edge of the range, not by its value
        shares += std::min(std::max(static_cast<double>(lambda) * sigma, n_min), n_max);
        counted += counts[i];
        ++histogram_pixels;
    }
    const double plan = static_cast<double>(p.budget) * static_cast<double>(histogram_pixels + h.zero_pixels);
    double bound = plan * (0x1.0p-13 + 0x1.0p-15);
    for (std::uint32_t b = 0; b < EMCV_BUDGET_BINS; ++b) {
        const double octave = std::ldexp(1.0, EMCV_BUDGET_SIGMA_LOW_EXPONENT + static_cast<int>(b / 8));
        const double lo = octave * (1 + (b % 8) / 8.0), hi = lo + octave / 8;
        for (const double c : {n_min, n_max})
            if (lambda * lo <= c && c <= lambda * hi) bound += h.bin_count[b] * c * (hi / lo - 1);
    }
    EMCV_FUZZ_ASSERT(std::fabs(shares - plan) <= bound);
    EMCV_FUZZ_ASSERT(std::fabs(counted - shares) <= static_cast<double>(histogram_pixels));
}

template <class State>
void plan(const emcv::sampling_params& p, frame_state<State>& fs, input& in) {
    const std::uint8_t what = in.byte();
    if (what & 1u) {  // new materials: 0 (no scattering) or one of two ids
        fs.with_material = true;
        for (auto& m : fs.material) m = in.byte() % 3u;
    }
    if (what & 2u) fs.with_material = false;
    if (what & 4u) {
        fs.with_sub_pixel = true;
        for (auto& s : fs.sub_pixel) s = in.byte() % 4u == 0u ? 1u : 0u;
    }
    if (what & 8u) fs.with_sub_pixel = false;
    const std::uint32_t frame = in.bits<std::uint32_t>(), seed = in.bits<std::uint32_t>();
    const std::uint32_t* material = fs.with_material ? fs.material.data() : nullptr;
    const std::uint8_t* sub_pixel = fs.with_sub_pixel ? fs.sub_pixel.data() : nullptr;
    const std::vector<State> before = fs.history;

    emcv::frame_plan result;
    try {
        result = emcv::plan_frame(p, fs.history.data(), fs.pixels, fs.width, material, sub_pixel, frame, seed,
                                  fs.sigma2.data(), fs.counts.data());
        EMCV_FUZZ_ASSERT(params_valid(p));
    } catch (const std::invalid_argument&) {
        EMCV_FUZZ_ASSERT(!params_valid(p));
        return;
    }
    for (std::size_t i = 0; i < fs.pixels; ++i) EMCV_FUZZ_ASSERT(same_bits(fs.history[i], before[i]));  // const

    const bool all_valid = std::all_of(fs.history.begin(), fs.history.end(), [](const State& s) { return valid(s); });
    const bool has_control = p.estimator != emcv::sampling_estimator::spvg;
    const float no_samples = emcv::port::emcv_history_no_samples(), no_variance = emcv::port::emcv_history_no_variance();
    std::uint64_t sum = 0;
    for (std::size_t i = 0; i < fs.pixels; ++i) {
        const float s2 = fs.sigma2[i];
        const int n = fs.counts[i];
        sum += static_cast<std::uint64_t>(static_cast<std::uint32_t>(n));
        const bool scatters = material == nullptr || material[i] != 0u;
        if (!scatters || (has_control && sub_pixel != nullptr && sub_pixel[i] != 0u)) {
            EMCV_FUZZ_ASSERT(s2 == no_samples && n == 0);
            continue;
        }
        if (all_valid) EMCV_FUZZ_ASSERT(s2 >= 0.0f || s2 == no_variance);  // never NaN from valid histories
        if (p.mode == emcv::sampling_mode::quality_target || s2 >= 0.0f) {
            EMCV_FUZZ_ASSERT(n >= p.n_min && n <= p.n_max);
        } else {  // no variance (or NaN from an overwritten history): the budget itself
            const float b = std::min(p.budget, static_cast<float>(p.n_max));
            EMCV_FUZZ_ASSERT(static_cast<double>(n) >= std::floor(b) && static_cast<double>(n) <= std::ceil(b));
        }
    }
    EMCV_FUZZ_ASSERT(result.samples == sum);
    if (p.mode == emcv::sampling_mode::quality_target) {
        EMCV_FUZZ_ASSERT(result.lambda == 0.0f);
        return;
    }
    emcv::budget_histogram h = emcv::make_budget_histogram();
    emcv::budget_add(h, fs.sigma2.data(), fs.pixels, material);
    const float lambda = emcv::budget_solve(p, h);
    EMCV_FUZZ_ASSERT(std::memcmp(&lambda, &result.lambda, sizeof lambda) == 0 && emcv::budget_solve(p, h) == lambda);
    check_budget_sum(p, fs.sigma2, material, lambda, h, fs.counts);
}

template <class State>
void update(const emcv::sampling_params& p, frame_state<State>& fs, input& in) {
    const std::uint8_t what = in.byte();
    std::vector<float> f(fs.pixels), g(fs.pixels);
    std::vector<int> taken = fs.counts;
    if (what & 1u) {  // a noisy stream f = G (1 + noise), G of the frame's light
        const float light = static_cast<float>(in.byte()) / 64.0f;
        for (std::size_t i = 0; i < fs.pixels; ++i) {
            g[i] = light * (0.25f + static_cast<float>(i % fs.width) / static_cast<float>(fs.width));
            f[i] = g[i] * (1.0f + static_cast<float>(static_cast<std::int8_t>(in.byte())) / 256.0f);
        }
    } else {  // hard cases and raw bits
        for (std::size_t i = 0; i < fs.pixels; ++i) {
            f[i] = in.scalar<float>();
            g[i] = in.scalar<float>();
        }
    }
    if (what & 2u)
        for (auto& t : taken) t = any_int(in);
    const bool null_g = (what & 4u) != 0u;  // documented as allowed for spvg only
    const std::uint32_t* material = fs.with_material ? fs.material.data() : nullptr;
    const std::vector<State> before = fs.history;
    try {
        emcv::sampling_update(p, fs.history.data(), fs.pixels, fs.width, material, f.data(), null_g ? nullptr : g.data(),
                              taken.data());
        EMCV_FUZZ_ASSERT(params_valid(p) && (!null_g || p.estimator == emcv::sampling_estimator::spvg));
    } catch (const std::invalid_argument&) {
        EMCV_FUZZ_ASSERT(!params_valid(p) || (null_g && p.estimator != emcv::sampling_estimator::spvg));
        for (std::size_t i = 0; i < fs.pixels; ++i) EMCV_FUZZ_ASSERT(same_bits(fs.history[i], before[i]));
        return;
    }
    for (std::size_t i = 0; i < fs.pixels; ++i) {
        const State &s = fs.history[i], &old = before[i];
        if (taken[i] <= 0 || (material != nullptr && material[i] == 0u)) {  // nothing learnt
            EMCV_FUZZ_ASSERT(same_bits(s, old));
            continue;
        }
        if (refused(p, f[i], null_g ? 0.0f : g[i])) {
            State expected = old;
            expected.rejected += 1u;
            EMCV_FUZZ_ASSERT(same_bits(s, expected));
            continue;
        }
        EMCV_FUZZ_ASSERT(s.rejected == old.rejected);
        const bool reseeded = old.count != 0u && !valid(old);
        EMCV_FUZZ_ASSERT(s.reseeded == old.reseeded + (reseeded ? 1u : 0u));
        const bool mature = double(old.count) * double(emcv::sampling_eta(p)) >= 1.0;
        if (reseeded || p.estimator != emcv::sampling_estimator::cv || !mature) {
            EMCV_FUZZ_ASSERT(s.count == (reseeded ? 1u : old.count + 1u));
        } else {  // cv may lower a mature history's count where f's level moved (port::emcv_history_level_bias)
            EMCV_FUZZ_ASSERT(s.count >= 2u && s.count <= old.count + 1u);
        }
        // a valid state stays valid; an invalid one is replaced (reseeded) unless it claims no samples yet
        if (valid(old) || old.count != 0u) EMCV_FUZZ_ASSERT(valid(s));
    }
}

template <class State, class Other>
void run(const emcv::sampling_params& p, input& in) {
    frame_state<State> fs;
    fs.width = 1u + in.byte() % 16u;
    fs.pixels = fs.width * (1u + in.byte() % 16u);
    fs.history.assign(fs.pixels, init(State{}));
    fs.material.assign(fs.pixels, 1u);
    fs.sub_pixel.assign(fs.pixels, 0u);
    fs.sigma2.assign(fs.pixels, 0.0f);
    fs.counts.assign(fs.pixels, 0);

    // the wrong state type is refused, whatever the parameters
    std::vector<Other> other(fs.pixels, init(Other{}));
    try {
        emcv::plan_frame(p, other.data(), fs.pixels, fs.width, nullptr, nullptr, 0u, 0u, fs.sigma2.data(),
                         fs.counts.data());
        EMCV_FUZZ_ASSERT(false);
    } catch (const std::invalid_argument&) {
    }
    std::fill(fs.counts.begin(), fs.counts.end(), 0);

    for (int op_count = 0; !in.empty() && op_count < 64; ++op_count) {
        const std::uint8_t op = in.byte() % 8;
        if (op < 3) {
            plan(p, fs, in);
        } else if (op < 6) {
            update(p, fs, in);
        } else if (op == 6) {
            const std::size_t i = in.byte() % fs.pixels;
            const std::uint8_t which = in.byte();
            poke(fs.history[i], which, in.scalar<float>());
        } else {
            const std::size_t i = in.byte() % fs.pixels;
            fs.history[i] = init(State{});
        }
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    input in(data, size);
    emcv::sampling_params p;
    const std::uint8_t selector = in.byte();
    p.estimator = static_cast<emcv::sampling_estimator>(selector % 3);
    p.mode = (selector / 3) % 2 == 0 ? emcv::sampling_mode::quality_target : emcv::sampling_mode::budget;
    const std::uint8_t which = in.byte();  // each value: the default, or a fuzzer-chosen one
    if (which & 1u) p.target = in.scalar<float>();
    if (which & 2u) p.budget = (which & 64u) ? static_cast<float>(in.byte()) / 4.0f : in.scalar<float>();
    if (which & 4u) p.n_min = any_int(in);
    if (which & 8u) p.n_max = any_int(in);
    if (which & 16u) p.eta = (which & 128u) ? static_cast<float>(in.byte()) / 256.0f : in.scalar<float>();

    bool threw = false;
    try {
        emcv::check_sampling_params(p);
    } catch (const std::invalid_argument&) {
        threw = true;
    }
    EMCV_FUZZ_ASSERT(threw == !params_valid(p));

    if (p.estimator == emcv::sampling_estimator::cv) run<EmcvEmcm2, EmcvMovingStats>(p, in);
    else run<EmcvMovingStats, EmcvEmcm2>(p, in);
    return 0;
}
