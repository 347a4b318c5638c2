// SPDX-License-Identifier: MIT
// The per-sample variance a pixel is allocated with is pooled as shaders/adaptive/samples.comp.glsl pools it
// (sampling_pool): the mean over the pixel's 3x3 neighbours that lie in the image and in its 8x8 tile (tiles
// aligned at multiples of 8) and have its material, itself included; codes (no variance, no samples) are
// neither pooled nor changed; material 0 does not scatter (no samples, never pooled).
//   reference   an independent loop over the rule above, in the shader's order (dy outer, dx inner, float
//               sums): sampling_pool equals it bit for bit on a random field of materials, variances and codes
//               whose size is not a multiple of the tile (partial tiles at the right and bottom edges), in
//               place as out of place.
//   tiles       a field of 8x8 tiles alternating sigma 1 and 4: every pooled value is its tile's own, exactly
//               (k equal values summed and divided by k), so no tile ever reads its neighbour.
//   materials   a pixel checkerboard of two materials with sigma^2 1 and 16: pooled = own, exactly.
//   outlier     a constant field 1 with one pixel 10 inside a tile: the outlier and each of its 8 neighbours pool
//               (8 + 10) / 9 = 2, exactly; pixels two away are untouched.
//   codes       a code keeps its slot and is not counted in its neighbours' means.
//   the frame   plan_frame allocates from the pooled codes, and leaves material-0 pixels out of the budget.
#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <emcv/adaptive_sampling.hpp>

#include "policy_support.hpp"

namespace pooling_tests {  // one namespace per file: the unity build (the sanitize preset) joins files

namespace {

constexpr float no_variance = -1.0f, no_samples = -2.0f;

/// The pooling rule written out independently of the library and of the port's pool functions.
std::vector<float> reference_pool(const std::vector<float>& own, const std::vector<std::uint32_t>& material,
                                  int width, int height) {
    std::vector<float> out(own.size());
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y * width + x);
            if (material[i] == 0u) {
                out[i] = no_samples;
                continue;
            }
            if (own[i] < 0.0f) {
                out[i] = own[i];
                continue;
            }
            float sum = 0.0f;
            std::uint32_t count = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int qx = x + dx, qy = y + dy;
                    if (qx < 0 || qy < 0 || qx >= width || qy >= height) continue;
                    if (qx / 8 != x / 8 || qy / 8 != y / 8) continue;
                    const std::size_t q = std::size_t(qy * width + qx);
                    if (material[q] != material[i] || own[q] < 0.0f) continue;
                    sum += own[q];
                    ++count;
                }
            out[i] = sum / float(count);
        }
    return out;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (!(a[i] == b[i])) return false;
    return true;
}

}  // namespace

TEST_CASE("sampling_pool: the shader's 3x3 same-material in-tile mean, bit for bit, in place too") {
    constexpr int width = 21, height = 13;  // partial tiles on the right (5 wide) and at the bottom (5 high)
    constexpr std::size_t pixels = std::size_t(width * height);
    emcv_policy_test::gaussian_source rng(31);
    std::vector<float> own(pixels);
    std::vector<std::uint32_t> material(pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
        material[i] = std::uint32_t(rng.integer(0, 2));
        const int kind = rng.integer(0, 9);
        own[i] = kind == 0 ? no_variance : kind == 1 ? no_samples : float(1e-3 * (1 + 99 * rng.uniform()));
    }
    const std::vector<float> expected = reference_pool(own, material, width, height);
    std::vector<float> out(pixels);
    emcv::sampling_pool(own.data(), pixels, width, material.data(), out.data());
    CHECK(same_bits(out, expected));
    std::vector<float> in_place = own;
    emcv::sampling_pool(in_place.data(), pixels, width, material.data(), in_place.data());
    CHECK(same_bits(in_place, expected));
    // pooling did something: most pixels with a variance are not their own value
    std::size_t changed = 0;
    for (std::size_t i = 0; i < pixels; ++i)
        if (own[i] >= 0.0f && material[i] != 0u && out[i] != own[i]) ++changed;
    CHECK(changed > pixels / 4);
    // null material: every pixel scatters, one material
    const std::vector<std::uint32_t> one(pixels, 7u);
    emcv::sampling_pool(own.data(), pixels, width, nullptr, out.data());
    CHECK(same_bits(out, reference_pool(own, one, width, height)));
    CHECK_THROWS_AS(emcv::sampling_pool(own.data(), pixels, 4, nullptr, out.data()), std::invalid_argument);
    CHECK_THROWS_AS(emcv::sampling_pool(nullptr, pixels, width, nullptr, out.data()), std::invalid_argument);
}

TEST_CASE("sampling_pool never mixes tiles, nor materials") {
    constexpr std::size_t side = 16, pixels = side * side;
    std::vector<float> own(pixels), out(pixels);
    for (std::size_t y = 0; y < side; ++y)
        for (std::size_t x = 0; x < side; ++x) own[y * side + x] = ((x / 8 + y / 8) % 2 == 0) ? 1.0f : 16.0f;
    emcv::sampling_pool(own.data(), pixels, side, nullptr, out.data());
    CHECK(same_bits(out, own));

    std::vector<std::uint32_t> material(pixels);
    for (std::size_t y = 0; y < side; ++y)
        for (std::size_t x = 0; x < side; ++x) {
            material[y * side + x] = 1u + std::uint32_t((x + y) % 2);
            own[y * side + x] = material[y * side + x] == 1u ? 1.0f : 16.0f;
        }
    emcv::sampling_pool(own.data(), pixels, side, material.data(), out.data());
    CHECK(same_bits(out, own));
}

TEST_CASE("sampling_pool averages an outlier with its 8 neighbours and leaves codes alone") {
    constexpr std::size_t side = 8, pixels = side * side;
    std::vector<float> own(pixels, 1.0f), out(pixels);
    own[3 * side + 3] = 10.0f;
    emcv::sampling_pool(own.data(), pixels, side, nullptr, out.data());
    for (std::size_t y = 0; y < side; ++y)
        for (std::size_t x = 0; x < side; ++x) {
            const bool near = x >= 2 && x <= 4 && y >= 2 && y <= 4;
            INFO("pixel (" << x << ", " << y << ")");
            CHECK(out[y * side + x] == (near ? 2.0f : 1.0f));
        }

    // a code in the middle of a field of 4: it stays; its neighbours average the variances around them only
    // (a code counted as a value, or counted at all, would pull them below 4)
    std::fill(own.begin(), own.end(), 4.0f);
    own[3 * side + 3] = no_variance;
    own[5 * side + 5] = no_samples;
    emcv::sampling_pool(own.data(), pixels, side, nullptr, out.data());
    CHECK(out[3 * side + 3] == no_variance);
    CHECK(out[5 * side + 5] == no_samples);
    for (std::size_t i = 0; i < pixels; ++i)
        if (own[i] >= 0.0f) CHECK(out[i] == 4.0f);

    // material 0 does not scatter: no samples, and it never pools into its neighbours
    std::vector<std::uint32_t> material(pixels, 3u);
    std::fill(own.begin(), own.end(), 1.0f);
    own[1] = 100.0f;
    material[1] = 0u;
    emcv::sampling_pool(own.data(), pixels, side, material.data(), out.data());
    CHECK(out[1] == no_samples);
    for (std::size_t i = 0; i < pixels; ++i)
        if (i != 1) CHECK(out[i] == 1.0f);
}

TEST_CASE("plan_frame allocates from the pooled variances; pixels that do not scatter take nothing") {
    // spvg states with a known variance: sigma^2 = variance * unbias (count >= 2)
    constexpr std::size_t width = 16, pixels = width * 8;
    emcv::sampling_params p;
    p.mode = emcv::sampling_mode::budget;
    p.budget = 8;
    emcv_policy_test::gaussian_source rng(9);
    std::vector<emcv::port::EmcvMovingStats> states(pixels, emcv::port::emcv_moving_stats_init());
    std::vector<std::uint32_t> material(pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
        states[i].mean = 0.5f;
        states[i].variance = float(1e-3 * (1 + 9 * rng.uniform()));
        states[i].count = 50u;
        material[i] = (i % width) < 3 ? 0u : 1u + std::uint32_t(i % 2);  // 3 columns that do not scatter
    }
    std::vector<float> sigma2(pixels), own(pixels), pooled(pixels);
    std::vector<int> n(pixels);
    const emcv::frame_plan plan =
        emcv::plan_frame(p, states.data(), pixels, width, material.data(), nullptr, 4u, 2u, sigma2.data(), n.data());
    emcv::sampling_sigma2(p, states.data(), pixels, nullptr, own.data());
    emcv::sampling_pool(own.data(), pixels, width, material.data(), pooled.data());
    CHECK(same_bits(sigma2, pooled));
    // the histogram holds the scattering pixels only, so lambda is the one solved over them
    emcv::budget_histogram h = emcv::make_budget_histogram();
    emcv::budget_add(h, pooled.data(), pixels, material.data());
    CHECK(h.zero_pixels == 0u);
    CHECK(plan.lambda == emcv::budget_solve(p, h));
    std::vector<int> counts(pixels);
    CHECK(plan.samples == emcv::sampling_counts(p, pooled.data(), pixels, width, plan.lambda, 4u, 2u, counts.data()));
    CHECK(counts == n);
    std::uint64_t scattering = 0;
    for (std::size_t i = 0; i < pixels; ++i) {
        if (material[i] == 0u) CHECK(n[i] == 0);
        else ++scattering;
    }
    // B per scattering pixel (the histogram's resolution and the stochastic rounding aside)
    const double mean = double(plan.samples) / double(scattering);
    INFO("mean samples per scattering pixel " << mean);
    CHECK(mean > 0.9 * p.budget);
    CHECK(mean < 1.1 * p.budget);
}

}  // namespace pooling_tests
