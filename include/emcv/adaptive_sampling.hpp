// SPDX-License-Identifier: MIT
/// \file
/// emcv adaptive sampling: the per-pixel sample-count policy of the adaptive SSS methods (spvg, cv,
/// cv-notex) as a C++ API over a frame's arrays, the same computation as the renderer's GPU passes.
//
// ABOUT      Per SSS pixel and frame (docs/integration.md):
//              plan_frame   the history's per-sample variance sigma^2 (supp. Eq. 25-27), pooled over the pixel's
//                           3x3 neighbours of its material in its 8x8 tile (sampling_pool), then the counts:
//                           quality target N = ceil(sigma^2 / target) clamped to [n_min, n_max], or a mean
//                           budget B spent as N = clamp(lambda sigma, n_min, n_max) rounded stochastically,
//                           lambda solved over a histogram of sigma, each pooled sigma^2 first shrunk towards
//                           the previous frame's mean (budget_prior, sampling_shrink: empirical Bayes,
//                           docs/renderer.md "Shrinkage");
//              the engine's SSS pass takes N samples per pixel;
//              sampling_update  pushes the frame's output f (the mean of its N samples) and its control G
//                           into the history as a batch of N (the comoments grow by N d d^T); cv's push is
//                           robust (port::emcv_history_push_cv: a jump the control does not explain enters
//                           with a 5-sigma weight and restarts the means; an explained move that carries f's
//                           level beyond 5 sigma lowers the count to the frames the variance measured at the
//                           old level is worth), and where the residuals of an 8x8 tile's pixels say the
//                           noise fell, their comoments are scaled down by the ratio (the tile's noise test).
//            Every formula is the port's (include/emcv/port/history.h, budget.h, ema.h, cv.h), the code the
//            GPU runs: this header only loops over pixels, in the order of shaders/adaptive/samples.comp.glsl
//            and the burley pass's count and history update. budget_solve finds the lambda that the GPU's
//            solve pass solves (shaders/module/emcv_adaptive_budget.glsl), bit for bit (the bins added in
//            the same order, the same float operations) when compiled without FMA contraction
//            (-ffp-contract=off, as the port asks).
//            The per-pixel states are the port's own types, so a history kept in a GPU storage buffer and
//            one kept here have the same layout: port::EmcvEmcm2 for cv (the EMCM over (f, G)),
//            port::EmcvMovingStats for spvg (moving stats of f) and cv-notex (of f - G).
//            Unlike the rest of emcv this header needs GLM (through the port): emcv.hpp includes it only
//            where <glm/glm.hpp> is found.
// USAGE      emcv::sampling_params p;  p.estimator = emcv::sampling_estimator::cv;
//            std::vector<emcv::port::EmcvEmcm2> states(pixels, emcv::port::emcv_emcm2_init());
//            emcv::plan_frame(p, states.data(), pixels, width, material.data(), nullptr, frame, seed, sigma2.data(),
//                             n.data());
//            ... render with n[i] samples ...;
//            emcv::sampling_update(p, states.data(), pixels, width, material.data(), f, g, n.data());
// REFERENCES Xie & Olano 2021 (Eq. 29, 31; supp. Eq. 21, 25-27); SPVG 2020 (eta 0.2, target 1e-4, N <= 64).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <type_traits>

#include "detail/common.hpp"
#include "port/history.h"

namespace emcv {

/// Which per-sample variance drives the counts (the adaptive methods of the renderer).
enum class sampling_estimator {
    spvg,     ///< moving mean/variance of f (SPVG 2020); state port::EmcvMovingStats
    cv,       ///< EMCM over (f, G), the residual variance C_ff - C_fG^2 / C_GG (Eq. 31); state port::EmcvEmcm2
    cv_notex  ///< moving mean/variance of f - G (the control at alpha = 1); state port::EmcvMovingStats
};

/// Every estimator, in the order the renderer's method table and the docs list them: the one list that the
/// parser below, the Python module and the renderer's tests iterate.
inline constexpr std::array<sampling_estimator, 3> sampling_estimators{sampling_estimator::spvg, sampling_estimator::cv,
                                                                      sampling_estimator::cv_notex};

/// The estimator's name, as the renderer's method (`emcv-demo --method`) spells it: "spvg", "cv", "cv-notex".
inline const char* sampling_estimator_name(sampling_estimator e) noexcept {
    switch (e) {
        case sampling_estimator::spvg: return "spvg";
        case sampling_estimator::cv: return "cv";
        case sampling_estimator::cv_notex: return "cv-notex";
    }
    return "cv-notex";
}

/// The estimator a name spells: sampling_estimator_name's names, and "cv_notex" (a valid identifier, as the Python
/// module spells it); nullopt for anything else.
inline std::optional<sampling_estimator> parse_sampling_estimator(std::string_view name) noexcept {
    for (const sampling_estimator e : sampling_estimators)
        if (name == sampling_estimator_name(e)) return e;
    if (name == "cv_notex") return sampling_estimator::cv_notex;
    return std::nullopt;
}

/// How the per-sample variances become counts.
enum class sampling_mode {
    quality_target,  ///< N = ceil(sigma^2 / target) clamped to [n_min, n_max]: each output's variance on target
    budget           ///< a mean of `budget` samples per pixel, N proportional to sigma (least mean squared error)
};

/// The eta the renderer uses for an estimator: EMCV_HISTORY_ETA_EMCM (0.2, SPVG's rather than the paper's 0.05:
/// docs/renderer.md, "The memory") for cv,
/// EMCV_HISTORY_ETA_MOVING (SPVG's 0.2) for spvg and cv-notex.
inline float sampling_default_eta(sampling_estimator e) noexcept {
    return e == sampling_estimator::cv ? EMCV_HISTORY_ETA_EMCM : EMCV_HISTORY_ETA_MOVING;
}

/// The largest n_max accepted: the budget's solve searches lambda for counts up to 2^10 (port/budget.h,
/// emcv_budget_lambda_high_bits), the port's N_MAX range; a larger count is not exact in the fp32 arithmetic the
/// counts are computed in once past 2^24 (a cap of 50332419 rounded to 50332420).
inline constexpr int sampling_n_max_limit = 1024;

/// The policy's parameters; check_sampling_params says which values are accepted. The defaults are the
/// port's tunables (include/emcv/port/history.h), so an engine's CPU plan and the renderer's GPU passes agree
/// unless told otherwise.
struct sampling_params {
    sampling_estimator estimator = sampling_estimator::spvg;  ///< the variance that drives the counts
    sampling_mode mode = sampling_mode::quality_target;       ///< quality target or budget
    float target = EMCV_HISTORY_TARGET;  ///< quality target: the output variance aimed at, finite and > 0
    float budget = 8.0f;                 ///< budget mode: mean samples per pixel, in (0, n_max]
    int n_min = EMCV_HISTORY_N_MIN;      ///< fewest samples of a pixel whose kernel is wider than a pixel, >= 1
    int n_max = EMCV_HISTORY_N_MAX;      ///< most samples of a pixel, in [n_min, sampling_n_max_limit]
    std::optional<float> eta;            ///< history weight in (0, 0.5]; empty: sampling_default_eta(estimator)
};

/// The history weight p uses: p.eta, or the estimator's default when it is empty.
inline float sampling_eta(const sampling_params& p) noexcept {
    return p.eta ? *p.eta : sampling_default_eta(p.estimator);
}

/// Throws std::invalid_argument naming the first broken requirement: n_min >= 1, n_min <= n_max,
/// n_max <= sampling_n_max_limit (1024), eta in (0, 0.5], and the mode's own value (quality target: target
/// finite and > 0; budget: budget finite, > 0 and <= n_max). The other mode's value is not read, so it is not checked.
inline void check_sampling_params(const sampling_params& p) {
    constexpr const char* where = "emcv::sampling_params";
    detail::require_value(p.n_min >= 1, where, "n_min", p.n_min,
                          "must be >= 1 (a pixel at 0 would never learn its noise)");
    if (p.n_min > p.n_max)
        detail::throw_invalid_value(where, "n_min", p.n_min,
                                    ("must not exceed n_max = " + std::to_string(p.n_max)).c_str());
    detail::require_value(p.n_max <= sampling_n_max_limit, where, "n_max", p.n_max,
                          "must not exceed 1024 (sampling_n_max_limit: the budget solve's range)");
    const float eta = sampling_eta(p);
    detail::require_value(eta > 0.0f && eta <= 0.5f, where, "eta", eta, "must lie in (0, 0.5]");
    if (p.mode == sampling_mode::quality_target)
        detail::require_value(std::isfinite(p.target) && p.target > 0.0f, where, "target", p.target,
                              "must be finite and > 0");
    else
        detail::require_value(std::isfinite(p.budget) && p.budget > 0.0f && p.budget <= static_cast<float>(p.n_max),
                              where, "budget", p.budget, "must be finite, > 0 and <= n_max");
}

namespace detail {

template <class State>
constexpr bool is_sampling_state =
    std::is_same<State, port::EmcvEmcm2>::value || std::is_same<State, port::EmcvMovingStats>::value;

/// The estimator's state type must be the one passed: cv keeps an EMCM, the others moving stats.
template <class State>
void check_state_type(const sampling_params& p, const char* where) {
    static_assert(is_sampling_state<State>, "the states are port::EmcvEmcm2 (cv) or port::EmcvMovingStats");
    const bool emcm = std::is_same<State, port::EmcvEmcm2>::value;
    require(emcm == (p.estimator == sampling_estimator::cv), where,
            "the states must be port::EmcvEmcm2 for cv and port::EmcvMovingStats for spvg and cv_notex");
}

inline void check_pixels(const void* pointer, std::size_t pixels, const char* where, const char* what) {
    require(pointer != nullptr || pixels == 0, where, what);
}

/// The checks every per-pixel read of the states starts with: valid parameters, the estimator's state type,
/// states and output arrays not null.
template <class State>
void check_state_read(const sampling_params& p, const State* states, std::size_t pixels, const float* out,
                      const char* where) {
    check_sampling_params(p);
    check_state_type<State>(p, where);
    check_pixels(states, pixels, where, "states must not be null");
    check_pixels(out, pixels, where, "out must not be null");
}

/// One pixel's push, as the burley pass's history update (shaders/module/emcv_adaptive_history.glsl; n > 0 only).
inline void push(const sampling_params&, float eta, port::EmcvEmcm2& s, float f, float g, float n) {
    port::emcv_history_push_cv(s, f, g, eta, n);
}
inline void push(const sampling_params& p, float eta, port::EmcvMovingStats& s, float f, float g, float n) {
    if (p.estimator == sampling_estimator::cv_notex)
        port::emcv_history_push_notex(s, f, g, eta, n);
    else
        port::emcv_moving_stats_push_batch(s, f, eta, n);
}

inline float sigma2_of(const port::EmcvEmcm2& s, float eta) { return port::emcv_history_sigma2_cv(s, eta); }
inline float sigma2_of(const port::EmcvMovingStats& s, float eta) { return port::emcv_history_sigma2_moving(s, eta); }
template <class State>
float frames_of(const State& s, float eta) {
    return port::emcv_history_effective_frames(s.count, eta);
}

}  // namespace detail

/// The side of the pooling tiles: the renderer's SSS tiles and workgroups (EMCV_RENDER_TILE_SIZE in
/// shaders/render/bindings.h), aligned at multiples of it from the image's pixel (0, 0). Neither the pooling nor
/// cv's noise test reaches across a tile's edge.
inline constexpr std::size_t sampling_tile_size = 8;

/// Pushes each pixel's frame into its history, as the renderer's adaptive burley pass does after sampling: f is
/// the pixel's output (the mean of the taken[i] samples it took), g its in-frame control G (both as the tracked scalar,
/// e.g. gamma-space luminance); the push is a batch of taken[i] (supp. Eq. 25-27), so the history estimates
/// the variance of one sample. spvg pushes f (port::emcv_moving_stats_push_batch), cv-notex f - G
/// (port::emcv_history_push_notex: the change test below at alpha = 1, no level's bias, no noise test); cv
/// pushes the pair (f, G) through port::emcv_history_push_cv: once the history is 1 / eta frames old, a residual
/// move beyond 5 sigma that G's move does not explain enters with the weight of a 5-sigma move and restarts
/// the means at (f, G); where a move the control explains still carries f's level beyond 5 sigma, the count is
/// lowered to the frames the variance measured at the old level is worth (port::emcv_history_level_bias).
/// cv then runs the tile's noise test: each pixel's term before its push (port::emcv_history_noise_term) is
/// pooled over the scattering pixels of its sampling_tile_size tile that took samples (port::emcv_history_noise_add,
/// exact fixed-point sums), and where the pool says the noise fell, every such pixel's comoments are scaled by the
/// ratio (port::emcv_history_noise_ratio, port::emcv_history_rescale_cv) after its push.
/// A pixel with taken[i] <= 0, or of material 0 (it does not scatter), learns nothing about its noise and is
/// left as it is; a non-finite f or G is refused by the port (state unchanged, `rejected` + 1). The arrays hold
/// `pixels` entries in rows of `width` (the image plan_frame planned); material may be null (every pixel
/// scatters, one material); g may be null for spvg only.
/// Throws std::invalid_argument when the parameters are invalid, the state type is not the estimator's, a
/// needed array is null, or width is 0 or does not divide pixels.
template <class State>
void sampling_update(const sampling_params& p, State* states, std::size_t pixels, std::size_t width,
                     const std::uint32_t* material, const float* f, const float* g, const int* taken) {
    constexpr const char* where = "emcv::sampling_update";
    check_sampling_params(p);
    detail::check_state_type<State>(p, where);
    detail::check_pixels(states, pixels, where, "states must not be null");
    detail::check_pixels(f, pixels, where, "f must not be null");
    detail::check_pixels(taken, pixels, where, "taken must not be null");
    if (p.estimator != sampling_estimator::spvg)
        detail::check_pixels(g, pixels, where, "g must not be null for cv and cv_notex");
    detail::require(width > 0 && pixels % width == 0, where, "width must be > 0 and divide the pixel count");
    const float eta = sampling_eta(p);
    const auto pushes = [&](std::size_t i) { return taken[i] > 0 && (material == nullptr || material[i] != 0u); };
    if constexpr (!std::is_same_v<State, port::EmcvEmcm2>) {
        for (std::size_t i = 0; i < pixels; ++i)
            if (pushes(i)) detail::push(p, eta, states[i], f[i], g != nullptr ? g[i] : 0.0f, static_cast<float>(taken[i]));
    } else {
        // One tile at a time, as the burley pass's workgroup: the tile's pool from every term before any push.
        constexpr std::size_t tile = sampling_tile_size;
        const std::size_t height = pixels / width;
        for (std::size_t y0 = 0; y0 < height; y0 += tile) {
            for (std::size_t x0 = 0; x0 < width; x0 += tile) {
                const std::size_t w = width - x0 < tile ? width - x0 : tile, h = height - y0 < tile ? height - y0 : tile;
                port::uvec3 pool(0u);
                for (std::size_t ly = 0; ly < h; ++ly)
                    for (std::size_t lx = 0; lx < w; ++lx) {
                        const std::size_t i = (y0 + ly) * width + x0 + lx;
                        if (!pushes(i)) continue;
                        const float n = static_cast<float>(taken[i]);
                        port::emcv_history_noise_add(pool, port::emcv_history_noise_term(states[i], f[i], g[i], eta, n),
                                                     port::emcv_history_noise_relative(n));
                    }
                const float ratio = port::emcv_history_noise_ratio(pool);
                for (std::size_t ly = 0; ly < h; ++ly)
                    for (std::size_t lx = 0; lx < w; ++lx) {
                        const std::size_t i = (y0 + ly) * width + x0 + lx;
                        if (!pushes(i)) continue;
                        port::emcv_history_push_cv(states[i], f[i], g[i], eta, static_cast<float>(taken[i]));
                        port::emcv_history_rescale_cv(states[i], ratio);
                    }
            }
        }
    }
}

/// Each pixel's own per-sample variance code, as the renderer's adaptive-samples pass computes it before
/// pooling (sampling_pool): port::emcv_history_sigma2_cv (cv) or port::emcv_history_sigma2_moving (spvg,
/// cv-notex), which is port::emcv_history_no_variance() for a history younger than two frames;
/// port::emcv_history_no_samples() where sub_pixel[i] is non-zero and the estimator has a control (cv,
/// cv-notex: a sub-pixel kernel's scattered value is its own diffuse). spvg has no control to stand in for it
/// and ignores sub_pixel, as the renderer does. sub_pixel may be null (no sub-pixel kernels). Pixels that do not
/// scatter get their code from sampling_pool (its material argument).
template <class State>
void sampling_sigma2(const sampling_params& p, const State* states, std::size_t pixels, const std::uint8_t* sub_pixel,
                     float* out) {
    detail::check_state_read(p, states, pixels, out, "emcv::sampling_sigma2");
    const float eta = sampling_eta(p);
    const bool skips = sub_pixel != nullptr && p.estimator != sampling_estimator::spvg;
    for (std::size_t i = 0; i < pixels; ++i)
        out[i] = skips && sub_pixel[i] != 0 ? port::emcv_history_no_samples() : detail::sigma2_of(states[i], eta);
}

/// Each pixel's effective frames, the number of frames its per-sample variance rests on
/// (port::emcv_history_effective_frames(count, eta): 0 before two frames, 1 at two, (2 - eta) / eta at saturation),
/// as the renderer's adaptive-samples pass computes it beside sampling_sigma2. Throws std::invalid_argument when
/// the parameters are invalid, the state type is not the estimator's, or an array is null.
template <class State>
void sampling_frames(const sampling_params& p, const State* states, std::size_t pixels, float* out) {
    detail::check_state_read(p, states, pixels, out, "emcv::sampling_frames");
    const float eta = sampling_eta(p);
    for (std::size_t i = 0; i < pixels; ++i) out[i] = detail::frames_of(states[i], eta);
}


namespace detail {

/// sampling_pool's tiles: pools `own` into `out` (which may be `own`) and calls pooled(i, frames) right after
/// writing out[i], with the pool's effective frames from own_frames(i) of its neighbours (0 where the pixel does
/// not scatter). One tile at a time through a copy, as the shader's shared memory: every neighbour pooled lies in
/// the pixel's tile, so writing a tile's results (out[i], and whatever pooled writes at i) never changes what
/// another tile reads.
template <class OwnFrames, class Pooled>
void pool_tiles(const float* own, std::size_t pixels, std::size_t width, const std::uint32_t* material, float* out,
                OwnFrames own_frames, Pooled pooled, const char* where) {
    require(width > 0 && pixels % width == 0, where, "width must be > 0 and divide the pixel count");
    constexpr std::size_t tile = sampling_tile_size;
    const std::size_t height = pixels / width;
    float tile_sigma2[tile * tile];
    float tile_frames[tile * tile];
    std::uint32_t tile_code[tile * tile];
    for (std::size_t y0 = 0; y0 < height; y0 += tile) {
        for (std::size_t x0 = 0; x0 < width; x0 += tile) {
            const std::size_t w = width - x0 < tile ? width - x0 : tile, h = height - y0 < tile ? height - y0 : tile;
            for (std::size_t ly = 0; ly < h; ++ly)
                for (std::size_t lx = 0; lx < w; ++lx) {
                    const std::size_t i = (y0 + ly) * width + x0 + lx;
                    tile_code[ly * tile + lx] = material != nullptr ? material[i] : 1u;
                    tile_sigma2[ly * tile + lx] = own[i];
                    tile_frames[ly * tile + lx] = own_frames(i);
                }
            for (std::size_t ly = 0; ly < h; ++ly)
                for (std::size_t lx = 0; lx < w; ++lx) {
                    const std::size_t here = ly * tile + lx, i = (y0 + ly) * width + x0 + lx;
                    const std::uint32_t code = tile_code[here];
                    if (code == 0u) {
                        out[i] = port::emcv_history_no_samples();
                        pooled(i, 0.0f);
                        continue;
                    }
                    float sum = 0.0f, inverse_frames = 0.0f;
                    std::uint32_t count = 0u;
                    // lx - 1 and ly - 1 wrap below 0 to a huge value: the `< w`, `< h` tests skip them as the
                    // shader skips q < 0.
                    for (std::size_t qy = ly - 1; qy != ly + 2; ++qy)
                        for (std::size_t qx = lx - 1; qx != lx + 2; ++qx) {
                            if (qx >= w || qy >= h || tile_code[qy * tile + qx] != code) continue;
                            port::emcv_history_pool_add_frames(inverse_frames, tile_sigma2[qy * tile + qx],
                                                               tile_frames[qy * tile + qx]);
                            port::emcv_history_pool_add(sum, count, tile_sigma2[qy * tile + qx]);
                        }
                    out[i] = port::emcv_history_pool_sigma2(tile_sigma2[here], sum, count);
                    pooled(i, port::emcv_history_pool_frames(count, inverse_frames));
                }
        }
    }
}

}  // namespace detail

/// The variance codes a frame is allocated with, as the renderer's adaptive-samples pass pools them: out[i] is
/// port::emcv_history_pool_sigma2(own[i], sum, count), sum and count accumulated by
/// port::emcv_history_pool_add over pixel i's 3x3 neighbours (dy then dx from -1 to 1, i itself included) that
/// lie in the image and in i's sampling_tile_size tile and have i's material; a code (negative own value) is
/// never pooled and a pixel holding one keeps it. material[i] == 0 marks a pixel that does not scatter: it
/// gets port::emcv_history_no_samples() (0 samples) and never pools with its neighbours; any other value is a
/// scattering material's id. material may be null: every pixel scatters, all with the same material. own and
/// out hold `pixels` entries in rows of `width` and may be the same array (pooling in place).
/// With own_frames (each pixel's effective frames, sampling_frames) and frames_out, frames_out[i] is the pooled
/// estimate's effective frames, port::emcv_history_pool_frames(count, sum of 1 / K_j by
/// port::emcv_history_pool_add_frames over the same neighbours), what the budget's shrinkage weighs it by
/// (0 for a pixel that does not scatter); own_frames and frames_out may be the same array. Both or neither.
/// Throws std::invalid_argument when own or out is null, only one of own_frames and frames_out is given, or
/// width is 0 or does not divide pixels.
inline void sampling_pool(const float* own, std::size_t pixels, std::size_t width, const std::uint32_t* material,
                          float* out, const float* own_frames = nullptr, float* frames_out = nullptr) {
    constexpr const char* where = "emcv::sampling_pool";
    detail::check_pixels(own, pixels, where, "own must not be null");
    detail::check_pixels(out, pixels, where, "out must not be null");
    detail::require((own_frames == nullptr) == (frames_out == nullptr), where,
                    "own_frames and frames_out must be given together (both or neither)");
    detail::pool_tiles(
        own, pixels, width, material, out,
        [own_frames](std::size_t i) { return own_frames != nullptr ? own_frames[i] : 0.0f; },
        [frames_out](std::size_t i, float frames) {
            if (frames_out != nullptr) frames_out[i] = frames;
        },
        where);
}

/// The budget's histogram of sigma: port::EmcvBudgetBlock, the storage block the GPU passes share (the same
/// layout, so it can be uploaded as it is).
using budget_histogram = port::EmcvBudgetBlock;

/// An empty histogram (every count 0, lambda and planned 0).
inline budget_histogram make_budget_histogram() noexcept {
    budget_histogram h{};
    return h;
}

/// Adds one pixel's variance code to the histogram, as the GPU's emcv_budget_add
/// (shaders/module/emcv_adaptive_budget.glsl): emcv_history_no_samples() counts as a zero pixel (its share goes to the
/// others), a code without a variance (negative or NaN) as a default pixel (it takes the budget itself, outside
/// the solve), a variance in the bin of its sigma.
inline void budget_add(budget_histogram& h, float sigma2) noexcept {
    if (sigma2 == port::emcv_history_no_samples()) {
        ++h.zero_pixels;
    } else if (!(sigma2 >= 0.0f)) {
        ++h.default_pixels;
    } else {
        const float sigma = std::sqrt(sigma2);
        const std::uint32_t bin = port::emcv_budget_bin(sigma);
        ++h.bin_count[bin];
        h.bin_fraction[bin] += port::emcv_budget_fraction(sigma);
    }
}

/// Adds every scattering pixel's variance code (budget_add): a pixel with material[i] == 0 does not scatter and
/// is left out, as the GPU's samples pass leaves it (it is not an SSS pixel, so the budget is not spent on its
/// behalf); material may be null (every pixel scatters). Throws std::invalid_argument when sigma2 is null.
inline void budget_add(budget_histogram& h, const float* sigma2, std::size_t pixels,
                       const std::uint32_t* material = nullptr) {
    detail::check_pixels(sigma2, pixels, "emcv::budget_add", "sigma2 must not be null");
    for (std::size_t i = 0; i < pixels; ++i)
        if (material == nullptr || material[i] != 0u) budget_add(h, sigma2[i]);
}

/// Adds one pixel's pooled variance before shrinkage and its pooled effective frames to the statistics the next
/// frame's shrinkage reads, as the GPU's emcv_budget_add_raw: the bin of its sigma in raw_count and
/// port::emcv_history_inverse_frames_units(frames) in raw_inverse_frames. A code (negative or NaN sigma2) or a
/// pixel without frames adds nothing.
inline void budget_add_raw(budget_histogram& h, float sigma2, float frames) noexcept {
    if (!(sigma2 >= 0.0f) || !(frames > 0.0f)) return;
    ++h.raw_count[port::emcv_budget_bin(std::sqrt(sigma2))];
    h.raw_inverse_frames += port::emcv_history_inverse_frames_units(frames);
}

/// The statistics a frame's budget shrinks each pixel's pooled variance towards (port::emcv_history_shrink_sigma2):
/// the previous frame's mean m of the pooled variances and the spread tau^2 of the true ones across pixels.
/// Zero (the default) means none yet: the variances are spent as they are, as on the renderer's first frames.
struct budget_prior {
    float mean_sigma2 = 0.0f;       ///< m, > 0 once a frame had pixels with a variance
    float between_variance = 0.0f;  ///< tau^2 >= 0 (0: the spread was all sampling noise: spend evenly)
};

/// r, the relative variance of one frame's term of a history's variance under p's budget
/// (port::emcv_history_frame_relative_variance at the residual's kurtosis and a batch of max(budget, 1)): the
/// renderer's port::emcv_history_spend_relative_variance() when p.budget is its EMCV_HISTORY_SPP_BUDGET.
inline float budget_relative_variance(const sampling_params& p) noexcept {
    return port::emcv_history_frame_relative_variance(port::emcv_history_residual_kurtosis(),
                                                      p.budget > 1.0f ? p.budget : 1.0f);
}

/// The prior the next frame shrinks towards, from the histogram's raw_count and raw_inverse_frames
/// (budget_add_raw): port::emcv_history_frame_prior of the bins' moments, added as the GPU's solve adds them
/// (each of the 64 threads its bins t, t + 64, ..., then the threads in order), bit for bit. Leaves the histogram
/// as it is. Throws std::invalid_argument when the parameters are invalid (p.budget is checked as under a budget).
inline budget_prior budget_frame_prior(const sampling_params& p, const budget_histogram& h) {
    sampling_params as_budget = p;
    as_budget.mode = sampling_mode::budget;
    check_sampling_params(as_budget);
    constexpr std::uint32_t threads = static_cast<std::uint32_t>(sampling_tile_size * sampling_tile_size);
    glm::vec3 moments(0.0f);
    for (std::uint32_t t = 0; t < threads; ++t) {
        glm::vec3 partial(0.0f);
        for (std::uint32_t bin = t; bin < EMCV_BUDGET_BINS; bin += threads)
            partial = port::emcv_history_moments_add(partial, bin, h.raw_count[bin]);
        moments += partial;
    }
    const glm::vec2 prior = port::emcv_history_frame_prior(moments, h.raw_inverse_frames, budget_relative_variance(p));
    return budget_prior{prior.x, prior.y};
}

/// Shrinks each pooled variance code in place towards the prior, as the renderer's samples pass does before the
/// budget's histogram: sigma2[i] = port::emcv_history_shrink_sigma2(sigma2[i], frames[i], prior.mean_sigma2,
/// prior.between_variance, budget_relative_variance(p)): a pixel without a variance yet gets the mean, one
/// resting on many frames keeps nearly its own; emcv_history_no_samples() stays. Throws std::invalid_argument
/// when the parameters are invalid or an array is null.
inline void sampling_shrink(const sampling_params& p, const budget_prior& prior, float* sigma2, const float* frames,
                            std::size_t pixels) {
    constexpr const char* where = "emcv::sampling_shrink";
    sampling_params as_budget = p;
    as_budget.mode = sampling_mode::budget;
    check_sampling_params(as_budget);
    detail::check_pixels(sigma2, pixels, where, "sigma2 must not be null");
    detail::check_pixels(frames, pixels, where, "frames must not be null");
    const float relative = budget_relative_variance(p);
    for (std::size_t i = 0; i < pixels; ++i)
        sigma2[i] = port::emcv_history_shrink_sigma2(sigma2[i], frames[i], prior.mean_sigma2, prior.between_variance,
                                                     relative);
}

/// The scale lambda with sum_i clamp(lambda sigma_i, n_min, n_max) = budget (histogram pixels + zero pixels)
/// over the histogram: the smallest bit pattern of lambda strictly between port::emcv_budget_lambda_low_bits()
/// and _high_bits() whose total, the bins' samples added in bin order (empty bins skipped: they add exactly 0),
/// reaches the plan, else the high bound. Found here by EMCV_BUDGET_SOLVE_STEPS bisection steps (`total <
/// planned` moves the low end, the high end is returned) and on the GPU by a 64-way search
/// (shaders/module/emcv_adaptive_budget.glsl); the total is monotone in lambda, so both find the same bits (compiled
/// with -ffp-contract=off). Unlike the shader it leaves the histogram as it is (clear it with
/// make_budget_histogram()).
/// Throws std::invalid_argument when the parameters are invalid (the mode need not be budget: p.budget is
/// checked as under a budget).
inline float budget_solve(const sampling_params& p, const budget_histogram& h) {
    sampling_params as_budget = p;
    as_budget.mode = sampling_mode::budget;
    check_sampling_params(as_budget);
    constexpr std::uint32_t bins = EMCV_BUDGET_BINS;
    float bin_sum[bins];
    std::uint32_t histogram_pixels = 0;
    for (std::uint32_t b = 0; b < bins; ++b) {
        bin_sum[b] = port::emcv_budget_bin_sum(b, h.bin_count[b], h.bin_fraction[b]);
        histogram_pixels += h.bin_count[b];
    }
    const float n_min = static_cast<float>(p.n_min), n_max = static_cast<float>(p.n_max);
    const float planned = p.budget * static_cast<float>(histogram_pixels + h.zero_pixels);
    std::uint32_t low = port::emcv_budget_lambda_low_bits(), high = port::emcv_budget_lambda_high_bits();
    for (int step = 0; step < EMCV_BUDGET_SOLVE_STEPS; ++step) {
        const std::uint32_t middle = low + (high - low) / 2u;
        const float lambda = port::emcv_bits_float(middle);
        float total = 0.0f;
        for (std::uint32_t b = 0; b < bins; ++b)
            if (h.bin_count[b] != 0u) total += port::emcv_budget_bin_samples(lambda, bin_sum[b], h.bin_count[b], n_min, n_max);
        if (total < planned) low = middle;
        else high = middle;
    }
    return port::emcv_bits_float(high);
}

/// The counts of a frame from its variance codes, as the renderer's burley pass takes them: under a quality
/// target port::emcv_history_count_quality(sigma2, target, n_min, n_max) (n_max without a variance); under a
/// budget port::emcv_history_count_budget(sigma2, lambda, budget, n_min, n_max, u) with
/// u = port::emcv_budget_u(x, y, frame, seed) at the pixel's (x, y) = (i % width, i / width) (the budget itself
/// without a variance). 0 for emcv_history_no_samples(). lambda is read under a budget only. Returns the sum
/// of the counts.
/// Throws std::invalid_argument when the parameters are invalid, an array is null, or width is 0 or does not
/// divide pixels.
inline std::uint64_t sampling_counts(const sampling_params& p, const float* sigma2, std::size_t pixels,
                                     std::size_t width, float lambda, std::uint32_t frame, std::uint32_t seed,
                                     int* out) {
    constexpr const char* where = "emcv::sampling_counts";
    check_sampling_params(p);
    detail::check_pixels(sigma2, pixels, where, "sigma2 must not be null");
    detail::check_pixels(out, pixels, where, "out must not be null");
    detail::require(width > 0 && pixels % width == 0, where, "width must be > 0 and divide the pixel count");
    std::uint64_t total = 0;
    if (p.mode == sampling_mode::quality_target) {
        for (std::size_t i = 0; i < pixels; ++i) {
            out[i] = port::emcv_history_count_quality(sigma2[i], p.target, p.n_min, p.n_max);
            total += static_cast<std::uint64_t>(out[i]);
        }
        return total;
    }
    for (std::size_t i = 0; i < pixels; ++i) {
        const float u = port::emcv_budget_u(static_cast<std::uint32_t>(i % width),
                                            static_cast<std::uint32_t>(i / width), frame, seed);
        out[i] = port::emcv_history_count_budget(sigma2[i], lambda, p.budget, p.n_min, p.n_max, u);
        total += static_cast<std::uint64_t>(out[i]);
    }
    return total;
}

/// What plan_frame decided for a frame.
struct frame_plan {
    float lambda = 0.0f;        ///< budget mode: the solved scale (0 under a quality target)
    std::uint64_t samples = 0;  ///< the sum of the counts
};

/// One frame's plan, as the renderer's adaptive-samples, budget and burley passes: sampling_sigma2 into
/// sigma2_out, pooled there by sampling_pool (the codes the counts are computed from), then under a budget
/// each pooled variance shrunk towards `prior` by its pooled effective frames (sampling_frames, sampling_shrink),
/// the histogram of the scattering pixels (budget_add) and budget_solve, then sampling_counts into counts_out.
/// Under a budget `prior` is read (last frame's statistics; budget_prior{} before the first frame) and replaced
/// by this frame's (budget_add_raw, budget_frame_prior), as the renderer's budget block carries them from one
/// frame to the next; under a quality target it is left as it is. sigma2_out holds the codes the counts were
/// computed from (under a budget: shrunk).
/// states, material, sub_pixel, sigma2_out and counts_out hold `pixels` entries in rows of `width` (the image,
/// pixels / width rows); material[i] is the pixel's material id, 0 where it does not scatter (0 samples, out of
/// the pooling and the budget), and may be null (every pixel scatters, one material); sub_pixel may be null (no
/// sub-pixel kernels). frame and seed salt the budget's stochastic rounding (the renderer passes its frame index
/// and seed). It allocates nothing. Throws std::invalid_argument as the functions it calls.
template <class State>
frame_plan plan_frame(const sampling_params& p, const State* states, std::size_t pixels, std::size_t width,
                      const std::uint32_t* material, const std::uint8_t* sub_pixel, std::uint32_t frame,
                      std::uint32_t seed, float* sigma2_out, int* counts_out, budget_prior& prior) {
    sampling_sigma2(p, states, pixels, sub_pixel, sigma2_out);
    frame_plan plan;
    if (p.mode == sampling_mode::budget) {
        // sampling_frames, sampling_pool, budget_add_raw and sampling_shrink in one sweep: each pixel's pooled
        // variance is added to the frame statistics and shrunk as soon as it is pooled, its own frames read from
        // the states, so no per-frame array is allocated.
        const float eta = sampling_eta(p);
        const float relative = budget_relative_variance(p);
        budget_histogram h = make_budget_histogram();
        detail::pool_tiles(
            sigma2_out, pixels, width, material, sigma2_out,
            [states, eta](std::size_t i) { return detail::frames_of(states[i], eta); },
            [&h, &prior, sigma2_out, relative](std::size_t i, float frames) {
                budget_add_raw(h, sigma2_out[i], frames);
                sigma2_out[i] = port::emcv_history_shrink_sigma2(sigma2_out[i], frames, prior.mean_sigma2,
                                                                 prior.between_variance, relative);
            },
            "emcv::plan_frame");
        const budget_prior next = budget_frame_prior(p, h);
        budget_add(h, sigma2_out, pixels, material);
        plan.lambda = budget_solve(p, h);
        prior = next;
    } else {
        sampling_pool(sigma2_out, pixels, width, material, sigma2_out);
    }
    plan.samples = sampling_counts(p, sigma2_out, pixels, width, plan.lambda, frame, seed, counts_out);
    return plan;
}

/// plan_frame without a prior carried between frames: every frame planned as the renderer plans its first
/// (under a budget the pooled variances are spent as they are, none shrunk). An engine that plans frame after
/// frame under a budget passes a budget_prior it keeps (the overload above).
template <class State>
frame_plan plan_frame(const sampling_params& p, const State* states, std::size_t pixels, std::size_t width,
                      const std::uint32_t* material, const std::uint8_t* sub_pixel, std::uint32_t frame,
                      std::uint32_t seed, float* sigma2_out, int* counts_out) {
    budget_prior none;
    return plan_frame(p, states, pixels, width, material, sub_pixel, frame, seed, sigma2_out, counts_out, none);
}

}  // namespace emcv
