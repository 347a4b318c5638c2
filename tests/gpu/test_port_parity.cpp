// SPDX-License-Identifier: MIT
// CPU <-> GPU parity of the shared port. The same seeded streams (shaders/tests/parity_stream.h: 512 pixels in
// 8 hard-case classes x 10^4 updates) go through
//   (a) the double C++ templates (emcv::emcm<double, 2>, emcv::cv_coefficient<double>),
//   (b) the port on the CPU (fp32, -ffp-contract=off),
//   (c) the port in a compute shader on EGL (Mesa llvmpipe in CI).
// (b) vs (c): bit-identical for the estimators (docs/porting.md section "Parity bounds": +, -, * are correctly
// rounded in GLSL 4.50 and EMCV_PRECISE forbids FMA contraction; llvmpipe divides with IEEE division);
// Burley sampling uses exp/log/pow, whose GLSL precision is a few ulp, see kBurleyUlp below.
// (a) vs (b): within the first-order rounding-error bound derived in docs/porting.md.
// A failure prints the first diverging element.
#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <vector>

#include <emcv/control_variate.hpp>
#include <emcv/emcm.hpp>
#include <emcv/port/bindings.h>
#include <emcv/port/burley.h>
#include <emcv/port/cv.h>
#include <emcv/port/ema.h>
#include <emcv/port/resolve.h>
#include <emcv/port/samples.h>

#include "../../shaders/tests/parity_bindings.h"
#include "../../shaders/tests/parity_stream.h"
#include "gl/debug.hpp"
#include "gl/handles.hpp"
#include "gl/program.hpp"
#include "gl_test_support.hpp"
#include "../support/source_dirs.hpp"

namespace port = emcv::port;

namespace {

constexpr std::uint32_t kPixels = 512;
constexpr std::uint32_t kUpdates = 10000;
constexpr std::uint32_t kSeed = 0x5eedu;
constexpr float kEtaCov = 0.05f;
constexpr float kEtaRes = 0.2f;
constexpr float kTarget = 1.0e-4f;
constexpr int kNMin = 0;
constexpr int kNMax = 64;
constexpr float kBurleyD = 0.7f;
constexpr std::uint32_t kVec4s = EMCV_PARITY_OUTPUT_VEC4S;
/// Burley sampling uses exp, log and pow, which GLSL 4.50 does not round correctly: exp/exp2 within
/// 3 + 2|x| ulp, log/log2 within 3 ulp outside [0.5, 2] and an ABSOLUTE 2^-21 inside, pow = exp2(y log2 x).
/// Relative: the pdf chains 2 exp (|x| <= ~10) and 3 correctly rounded operations: <= 2 (3 + 20) + 3 ulp,
/// rounded up to kBurleyUlp = 64. Absolute: the radii are 3d ln(c / 4u') (exact) and d (...)(-ln(1-u)) (SPVG)
/// where the log's argument lies in [0.5, 2] for small u, so the absolute 2^-21 of log plus <= 16 ulp of
/// G^{1/3} (relative 2^-19 on an argument ~1) gives |dr| <= 3d (2^-21 + 2^-19) < 3d 2^-18; the CDF moves by
/// p(r) |dr| <= (1/2d) 3d 2^-18 = 1.5 * 2^-18 plus its own two exp (<= 2^-19 on values <= 1): < 2^-17.
/// An element passes when within kBurleyUlp ulp OR within its absolute bound.
constexpr std::int64_t kBurleyUlp = 64;
double burley_absolute_bound(std::uint32_t field) {
    if (field == 12 || field == 13) return 3.0 * static_cast<double>(kBurleyD) * std::ldexp(1.0, -18);
    if (field == 14) return std::ldexp(1.0, -17);
    return 0.0;
}

struct params_std140 {
    std::uint32_t counts[4];
    float weights[4];
    std::int32_t budget[4];
};
static_assert(sizeof(params_std140) == 48, "std140 layout of ParityParams");

std::uint32_t bits(float x) {
    std::uint32_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
}

/// Distance in units in the last place; values of magnitude below the smallest normal count as equal to 0
/// (GLSL allows, and llvmpipe does, flush denormals to zero).
std::int64_t ulp_distance(float a, float b) {
    const float tiny = port::emcv_float_min_normal();
    if (std::fabs(a) < tiny) a = 0.0f;
    if (std::fabs(b) < tiny) b = 0.0f;
    if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b) ? 0 : INT64_MAX;
    auto ordered = [](float x) {
        const std::int64_t i = static_cast<std::int64_t>(bits(x));
        return i & 0x80000000LL ? 0x80000000LL - i : i;  // -0 and +0 both map to 0
    };
    const std::int64_t d = ordered(a) - ordered(b);
    return d < 0 ? -d : d;
}

/// (b): the port on the CPU, the exact transcription of port_parity.comp.glsl's main().
std::vector<glm::vec4> run_port_cpu() {
    std::vector<glm::vec4> out(kPixels * kVec4s);
    for (std::uint32_t pixel = 0; pixel < kPixels; ++pixel) {
        port::EmcvEmcm2 cov = port::emcv_emcm2_init();
        port::EmcvMovingStats res = port::emcv_moving_stats_init();
        glm::vec2 last(0.0f);
        for (std::uint32_t k = 0; k < kUpdates; ++k) {
            const glm::vec2 x = port::emcv_parity_sample(pixel, k, kUpdates, kSeed);
            const float alpha = port::emcv_cv_coefficient_emcm2(cov);
            port::emcv_moving_stats_push(res, port::emcv_cv_residual(x.x, alpha, x.y), kEtaRes);
            port::emcv_emcm2_push(cov, x, kEtaCov);
            last = x;
        }
        const float q = res.variance / kTarget;
        const int n = port::emcv_sample_count(res.variance, kTarget, kNMin, kNMax);
        const float u = port::emcv_uint_to_unit_float(port::emcv_pcg(pixel + 7u));
        const float r_exact = port::emcv_burley_sample_exact(u, kBurleyD);
        const std::uint32_t base = pixel * kVec4s;
        out[base + 0] = glm::vec4(cov.mean, cov.cov.x, cov.cov.y);
        out[base + 1] = glm::vec4(cov.cov.z, port::emcv_cv_coefficient_emcm2(cov), res.mean, res.variance);
        out[base + 2] = glm::vec4(static_cast<float>(n), glm::uintBitsToFloat(cov.count),
                                  glm::uintBitsToFloat(cov.rejected), q);
        out[base + 3] = glm::vec4(r_exact, port::emcv_burley_sample_spvg(u, kBurleyD),
                                  port::emcv_burley_cdf(r_exact, kBurleyD), port::emcv_burley_pdf(r_exact, kBurleyD));
        const float scale = std::ldexp(1.0f, -static_cast<int>(pixel % 32u));
        const glm::vec3 slope =
            port::emcv_resolve_guide_slope(scale * glm::vec3(cov.cov.z, cov.cov.x, res.variance),
                                           scale * glm::vec3(cov.cov.y, -cov.cov.y, res.variance * cov.mean.x), 9.0f);
        const glm::vec3 moved = port::emcv_resolve_guided_history(glm::vec3(cov.mean, res.mean), slope,
                                                                  glm::vec3(last, q),
                                                                  glm::vec3(cov.mean.y, cov.mean.x, res.variance));
        out[base + 4] = glm::vec4(slope.x, slope.z, moved.x, moved.z);
        const glm::vec3 guide_sums = scale * glm::vec3(cov.cov.z, cov.cov.x, res.variance);
        const glm::vec3 change = glm::vec3(last, q) - glm::vec3(cov.mean.y, cov.mean.x, res.variance);
        out[base + 5] = glm::vec4(port::emcv_resolve_guide_weight(change, guide_sums, 1.0f),
                                  port::emcv_resolve_guide_weight(change, guide_sums, 9.0f),
                                  port::emcv_resolve_guide_weight(change, guide_sums, 81.0f),
                                  port::emcv_resolve_guide_weight(0.5f * change, guide_sums, 9.0f));
    }
    return out;
}

/// (c): the same in a compute shader.
std::vector<glm::vec4> run_port_gpu() {
    emcv::gl::preprocess_options options;
    options.include_dirs = emcv_test::shader_include_dirs();
    emcv::gl::debug_group group("port parity");
    const auto prog = emcv::gl::program::compute(emcv_test::shader_dir() / "tests/port_parity.comp.glsl", options);
    const params_std140 params{{kPixels, kUpdates, kSeed, 0u},
                               {kEtaCov, kEtaRes, kTarget, kBurleyD},
                               {kNMin, kNMax, 0, 0}};
    auto ubo = emcv::gl::buffer::create();
    glNamedBufferStorage(ubo.id(), sizeof params, &params, 0);
    std::vector<glm::vec4> out(kPixels * kVec4s, glm::vec4(-1.0f));
    auto ssbo = emcv::gl::buffer::create();
    const auto bytes = static_cast<GLsizeiptr>(out.size() * sizeof(glm::vec4));
    glNamedBufferStorage(ssbo.id(), bytes, out.data(), 0);
    glBindBufferBase(GL_UNIFORM_BUFFER, EMCV_BINDING_PARITY_PARAMS, ubo.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EMCV_BINDING_PARITY_OUTPUT, ssbo.id());
    prog.use();
    glDispatchCompute(kPixels / EMCV_WORKGROUP_SIZE_X, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glFinish();
    glGetNamedBufferSubData(ssbo.id(), 0, bytes, out.data());
    return out;
}

const char* field_name(std::uint32_t f) {
    static const char* names[] = {"mean_f", "mean_G", "C_ff", "C_fG", "C_GG", "alpha", "res_mean", "res_var",
                                  "n", "count", "rejected", "q", "burley_r", "burley_r_spvg", "burley_cdf", "burley_pdf",
                                  "guide_slope_x", "guide_slope_z", "guided_x", "guided_z", "guide_weight_n1",
                                  "guide_weight_n9", "guide_weight_n81", "guide_weight_half"};
    return names[f];
}

}  // namespace

TEST_CASE("port parity: double C++ templates, port on the CPU, port in an EGL compute shader") {
    auto ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger debug;
    static_assert(kPixels % EMCV_WORKGROUP_SIZE_X == 0, "whole workgroups");

    const std::vector<glm::vec4> cpu = run_port_cpu();
    const std::vector<glm::vec4> gpu = run_port_gpu();
    REQUIRE(debug.error_count() == 0);

    // (b) vs (c), element by element; report the first divergence and the worst distance per field.
    constexpr std::uint32_t kFields = kVec4s * 4;
    std::int64_t worst[kFields] = {};
    std::string first;
    for (std::uint32_t pixel = 0; pixel < kPixels; ++pixel) {
        for (std::uint32_t f = 0; f < kFields; ++f) {
            const float b = cpu[pixel * kVec4s + f / 4][static_cast<int>(f % 4)];
            const float c = gpu[pixel * kVec4s + f / 4][static_cast<int>(f % 4)];
            const bool integer_field = f == 9 || f == 10;  // count, rejected: compared as bits
            const std::int64_t d = integer_field ? (bits(b) == bits(c) ? 0 : INT64_MAX) : ulp_distance(b, c);
            worst[f] = std::max(worst[f], d);
            const bool burley_field = f >= 12 && f < 16;  // the guide's fields after them: exact
            const std::int64_t bound = burley_field ? kBurleyUlp : 0;
            const bool within_absolute =
                burley_field && std::fabs(static_cast<double>(b) - static_cast<double>(c)) <= burley_absolute_bound(f);
            if (d > bound && !within_absolute && first.empty()) {
                std::ostringstream m;
                m.precision(9);
                m << "first diverging element: pixel " << pixel << " (class " << port::emcv_parity_class(pixel)
                  << ") field " << field_name(f) << ": cpu " << b << " gpu " << c << " (" << d << " ulp, bound "
                  << bound << ", absolute bound " << burley_absolute_bound(f) << ")";
                first = m.str();
            }
        }
    }
    std::ostringstream summary;
    for (std::uint32_t f = 0; f < kFields; ++f) summary << field_name(f) << " " << worst[f] << " ulp; ";
    INFO("worst CPU/GPU distance per field: " << summary.str());
    INFO(first);
    CHECK(first.empty());

    // (a) vs (b): the double templates on the same (float) samples, against the bound of docs/porting.md:
    //   B_mu  = 2 u X (1/eta + 4),   B_cov = 2 (3 u C / eta + 4 u D^2 + 2 D (B_mu + 2 u X)),
    //   |alpha_b - alpha_a| <= B_cov (1 + |alpha_a|) / (C_GG - B_cov) + 2 u |alpha_a|   (when C_GG > B_cov),
    // with u = 2^-24, X = max |x|, D = max |x - mu|, C = max |Cov| over the pixel's stream.
    const double u = std::ldexp(1.0, -24);
    std::string first_a;
    std::uint32_t checked_alpha = 0;
    double worst_ratio = 0.0;  // max |diff| / bound over all checked elements (printed, not asserted)
    for (std::uint32_t pixel = 0; pixel < kPixels; ++pixel) {
        emcv::emcm<double, 2> ref(static_cast<double>(kEtaCov));
        double x_max = 0.0, d_max = 0.0, c_max = 0.0;
        for (std::uint32_t k = 0; k < kUpdates; ++k) {
            const glm::vec2 xf = port::emcv_parity_sample(pixel, k, kUpdates, kSeed);
            const std::array<double, 2> x{xf.x, xf.y};
            if (!std::isfinite(x[0]) || !std::isfinite(x[1])) {
                ref.push(x);
                continue;
            }
            if (ref.count() > 0)
                for (std::size_t i = 0; i < 2; ++i) d_max = std::max(d_max, std::fabs(x[i] - ref.mean(i)));
            ref.push(x);
            for (std::size_t i = 0; i < 2; ++i) x_max = std::max(x_max, std::fabs(x[i]));
            for (std::size_t i = 0; i < 2; ++i)
                for (std::size_t j = 0; j < 2; ++j) c_max = std::max(c_max, std::fabs(ref.covariance(i, j)));
        }
        const double eta = kEtaCov;
        const double b_mu = 2.0 * u * x_max * (1.0 / eta + 4.0);
        const double b_cov = 2.0 * (3.0 * u * c_max / eta + 4.0 * u * d_max * d_max + 2.0 * d_max * (b_mu + 2.0 * u * x_max));
        const glm::vec4 o0 = cpu[pixel * kVec4s + 0];
        const glm::vec4 o1 = cpu[pixel * kVec4s + 1];
        const double got[5] = {o0.x, o0.y, o0.z, o0.w, o1.x};
        const double want[5] = {ref.mean(0), ref.mean(1), ref.covariance(0, 0), ref.covariance(0, 1),
                                ref.covariance(1, 1)};
        for (int f = 0; f < 5; ++f) {
            const double bound = f < 2 ? b_mu : b_cov;
            if (bound > 0.0) worst_ratio = std::max(worst_ratio, std::fabs(got[f] - want[f]) / bound);
            if (std::fabs(got[f] - want[f]) > bound && first_a.empty()) {
                std::ostringstream m;
                m.precision(12);
                m << "first element outside the double bound: pixel " << pixel << " (class "
                  << port::emcv_parity_class(pixel) << ") field " << field_name(static_cast<std::uint32_t>(f))
                  << ": port " << got[f] << " double " << want[f] << " |diff| " << std::fabs(got[f] - want[f])
                  << " bound " << bound;
                first_a = m.str();
            }
        }
        const double alpha_a = emcv::cv_coefficient(ref.covariance(0, 1), ref.covariance(1, 1));
        const double c_gg = ref.covariance(1, 1);
        if (c_gg > b_cov) {
            ++checked_alpha;
            const double bound = b_cov * (1.0 + std::fabs(alpha_a)) / (c_gg - b_cov) + 2.0 * u * std::fabs(alpha_a);
            worst_ratio = std::max(worst_ratio, std::fabs(o1.y - alpha_a) / bound);
            if (std::fabs(o1.y - alpha_a) > bound && first_a.empty()) {
                std::ostringstream m;
                m.precision(12);
                m << "alpha outside the double bound: pixel " << pixel << ": port " << o1.y << " double " << alpha_a
                  << " bound " << bound;
                first_a = m.str();
            }
        } else {
            // Var(G) is within rounding of 0 (class 4: constant control): both sides must give "no CV".
            if (port::emcv_parity_class(pixel) == 4u && first_a.empty() && !(o1.y == 0.0f && alpha_a == 0.0))
                first_a = "class 4 (constant G) must give alpha = 0 on both sides";
        }
    }
    INFO(first_a);
    INFO("largest |port - double| / bound: " << worst_ratio);
    CHECK(first_a.empty());
    CHECK(checked_alpha >= kPixels * 6 / 8);  // every class but the constant-G one (and its neighbours) checks alpha
    CHECK(debug.error_count() == 0);
}
