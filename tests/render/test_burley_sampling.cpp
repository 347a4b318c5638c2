// SPDX-License-Identifier: MIT
// The Burley radii the GPU draws (port/sss.h in a compute shader) follow the port's CDF: a chi-square test over
// K equiprobable bins; SPVG's approximate inverse CDF is a different distribution and the same test sees it.
#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

#include <emcv/port/burley.h>

#include "../gpu/gl_test_support.hpp"
#include "../support/source_dirs.hpp"
#include "gl/debug.hpp"
#include "gl/program.hpp"
#include "../../shaders/render/bindings.h"

namespace {

constexpr std::uint32_t sample_count = 1u << 18;  // 262144 radii
constexpr int bins = 64;

struct radii_params {
    std::uint32_t counts[4];
    float shape[4];
};

std::vector<float> gpu_radii(float d, bool approximate, std::uint32_t seed) {
    emcv::gl::preprocess_options pre;
    pre.include_dirs = emcv_test::shader_include_dirs();
    const emcv::gl::program program =
        emcv::gl::program::compute(emcv_test::shader_dir() / "tests/burley_radii.comp.glsl", pre);
    const radii_params params{{sample_count, seed, 3u, approximate ? 1u : 0u}, {d, 0.0f, 0.0f, 0.0f}};
    emcv::gl::buffer ubo = emcv::gl::buffer::create();
    glNamedBufferStorage(ubo.id(), sizeof params, &params, 0);
    emcv::gl::buffer out = emcv::gl::buffer::create();
    glNamedBufferStorage(out.id(), sample_count * sizeof(float), nullptr, 0);
    program.use();
    glBindBufferBase(GL_UNIFORM_BUFFER, EMCV_RENDER_TEST_PARAMS, ubo.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EMCV_RENDER_TEST_OUTPUT, out.id());
    glDispatchCompute(sample_count / 64u, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<float> radii(sample_count);
    glGetNamedBufferSubData(out.id(), 0, static_cast<GLsizeiptr>(radii.size() * sizeof(float)), radii.data());
    return radii;
}

/// Pearson's statistic over `bins` bins of equal probability under F: bin = floor(bins F(r)).
double chi_square(const std::vector<float>& radii, float d) {
    std::vector<double> observed(bins, 0.0);
    for (float r : radii) {
        const double f = emcv::port::emcv_burley_cdf(r, d);
        int b = static_cast<int>(f * bins);
        b = b < 0 ? 0 : (b >= bins ? bins - 1 : b);
        observed[static_cast<std::size_t>(b)] += 1.0;
    }
    const double expected = static_cast<double>(radii.size()) / bins;
    double x2 = 0.0;
    for (double o : observed) x2 += (o - expected) * (o - expected) / expected;
    return x2;
}

/// Upper alpha = 1e-3 quantile of chi-square with k = 63 degrees of freedom, Wilson-Hilferty:
/// k (1 - 2/(9k) + z sqrt(2/(9k)))^3 with z = 3.0902 (the standard normal's 0.999 quantile) = 103.4
/// (tables: 103.44). With fixed seeds the test is deterministic; a correct sampler fails it for 0.1% of seeds.
double critical_value() {
    const double k = bins - 1;
    const double z = 3.0902;
    const double a = 2.0 / (9.0 * k);
    return k * std::pow(1.0 - a + z * std::sqrt(a), 3.0);
}

}  // namespace

TEST_CASE("GPU Burley radii follow the port's CDF (chi-square with 64 bins over 2^18 samples)") {
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    const double critical = critical_value();
    CHECK(std::abs(critical - 103.44) < 0.5);
    for (float d : {0.05f, 0.7f, 12.0f}) {
        for (std::uint32_t seed : {1u, 2u}) {
            const double x2 = chi_square(gpu_radii(d, false, seed), d);
            INFO("d " << d << " mm, seed " << seed << ": X^2 = " << x2 << ", critical " << critical);
            CHECK(x2 < critical);
        }
    }
    CHECK(messenger.error_count() == 0);
}

TEST_CASE("SPVG's approximate inverse CDF is detectably not the exact distribution") {
    // The approximation r ~ d (2 + (c - 2) u) (-ln(1 - u)) is a sampling strategy whose density differs from
    // p(r); the weights divide by the exact pdf, so only variance changes. The chi-square test has the power
    // to see the difference at 2^18 samples (showing it would also catch a wrong exact sampler).
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    const double x2 = chi_square(gpu_radii(0.7f, true, 1u), 0.7f);
    INFO("X^2 = " << x2);
    CHECK(x2 > 4.0 * critical_value());  // measured X^2 = 892 at d = 0.7 mm, seed 1
    CHECK(messenger.error_count() == 0);
}
