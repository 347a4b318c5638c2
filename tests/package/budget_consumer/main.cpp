// SPDX-License-Identifier: MIT
// An OpenGL engine running emcv's budget mode on the GPU from the installed prefix alone: its own passes
// (plan, solve, count, update: *.comp.glsl beside this file) over its own bindings (app.glsl), built from the
// installed modules <prefix>/share/emcv/module/*.glsl and port headers <prefix>/include/emcv/port/*.h through a
// small include resolver of its own, run on a headless EGL context over a synthetic sequence: a still 36 x 20
// image (partial 8x8 tiles at two edges, two materials, a corner that does not scatter, a last column whose
// kernels are under a pixel) whose per-pixel noise grows from left to
// right, and a light that goes off over the left half at frame kSwitch. The host takes the samples (f and G of
// each pixel, from the counts the GPU planned) and the GPU updates its histories. Every frame, the counts and
// the histories are compared with the C++ library's budget recipe on the same frame (emcv::plan_frame with its
// prior carried, emcv::sampling_update), for each method in turn:
//   cv              (the EMCM over (f, G), RGBA32F + RG32F texels): counts and histories bit for bit;
//   spvg, cv-notex  (the moving-statistics layout, one RGBA16F texel): each stored field within one binary16 ulp
//                   of the C++ state's fp32 texel (half_ulp derives it), then the C++ states are replaced by
//                   the GPU's texels decoded, so the rounding never accumulates and the counts are bit for bit.
// Exit 0 and "budget consumer: OK" on success, 1 on a failure, 77 (CTest's SKIP_RETURN_CODE) without an EGL
// display unless EMCV_REQUIRE_GL=1.
#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <emcv/adaptive_sampling.hpp>
#include <emcv/port/host.hpp>

#include "../common/egl_headless.h"

namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 36;
constexpr int kHeight = 20;
constexpr int kPixels = kWidth * kHeight;
constexpr int kFrames = 60;
constexpr int kSwitch = 30;   // the left half's light goes off
constexpr std::uint32_t kSeed = 7;
constexpr float kBudget = 8.0f;  // samples per scattering pixel; the passes' EMCV_HISTORY_SPP_BUDGET

std::string read_text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + path.string());
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// `file`'s text with every `#include "name"` replaced by the named file's text (searched beside the including
/// file, then in each root): what an engine's shader pipeline does (or glslang's GL_GOOGLE_include_directive).
/// The modules and the port headers carry include guards, so a file included twice is harmless.
std::string resolve(const fs::path& file, const std::vector<fs::path>& roots, int depth = 0) {
    if (depth > 16) throw std::runtime_error("include depth over 16 at " + file.string());
    std::istringstream in(read_text(file));
    std::string out, line;
    while (std::getline(in, line)) {
        const auto at = line.find("#include \"");
        if (at == std::string::npos || line.find_first_not_of(" \t") != at) {
            out += line + "\n";
            continue;
        }
        const auto begin = at + 10, end = line.find('"', begin);
        const std::string name = line.substr(begin, end - begin);
        std::vector<fs::path> where{file.parent_path()};
        where.insert(where.end(), roots.begin(), roots.end());
        bool found = false;
        for (const fs::path& root : where) {
            if (fs::exists(root / name)) {
                out += resolve(root / name, roots, depth + 1);
                found = true;
                break;
            }
        }
        if (!found) throw std::runtime_error(file.string() + ": #include \"" + name + "\" found in no include root");
    }
    return out;
}

/// The synthetic scene: material 1, a second material (2) in the lower right whose noise is 4 times as high (the
/// pooling must keep them apart), and a 4 x 6 corner that does not scatter.
std::uint32_t material_of(int x, int y) {
    if (x < 4 && y < 6) return 0u;
    return x >= 20 && y >= 11 ? 2u : 1u;
}

/// A hash in [-1, 1) (the sample noise of pixel i at frame t).
float noise(std::uint32_t i, std::uint32_t t) {
    std::uint32_t h = i * 747796405u + t * 2891336453u + 12345u;
    h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
    h = (h >> 22u) ^ h;
    return static_cast<float>(h >> 8) / static_cast<float>(1u << 23) - 1.0f;
}

/// The tracked f (the mean of n samples) and G (the control) of pixel (x, y) at frame t.
void sample(int x, int y, int t, int n, float& f, float& g) {
    const float light = (t >= kSwitch && x < kWidth / 2) ? 0.15f : 1.0f;
    const float albedo = 0.6f + 0.075f * static_cast<float>((x * 7 + y * 3) % 5);
    const float sigma = (0.02f + 0.3f * static_cast<float>(x) / kWidth) * light *  // per sample
                        (material_of(x, y) == 2u ? 4.0f : 1.0f);
    g = light;
    f = albedo * light + sigma * 1.7f * noise(static_cast<std::uint32_t>(y * kWidth + x), static_cast<std::uint32_t>(t)) /
                             std::sqrt(static_cast<float>(n > 0 ? n : 1));
}

/// The moving-statistics layout's stored fields (mean, variance / unit: emcv_history_encode_stats) against the C++
/// port's: |gpu - cpu| <= kHalfUlps * half_ulp(cpu). The GPU's update computes the texel's fp32 value as the port
/// does, bit for bit (the same push and encode in the same order, built with -ffp-contract=off here and `precise`
/// there, as cv's bit-equal texels show), then its image store converts it once to binary16 (RGBA16F), which
/// picks one of cpu's two binary16 neighbours (the nearest; llvmpipe's the one towards zero: every field measured
/// here is cpu truncated). They are one binary16 ulp of cpu's binade apart, half_ulp(cpu) = 2^(e - 10) for
/// 2^e <= |cpu| < 2^(e + 1), e >= -14 (<= 2^-10 |cpu|), and 2^-24 below 2^-14 (subnormals): kHalfUlps = 1. A cpu
/// beyond binary16's largest number, 65504, fails. The count (z, an integer <= EMCV_HISTORY_MAX_COUNT, exact in
/// binary16) and w (0) are compared exactly.
/// The rounding does not accumulate: after each frame's comparison the C++ states are replaced by the GPU's texels
/// decoded (emcv_history_decode_stats: what the GPU decodes next frame), so each frame's planning starts from the
/// same states on both sides and its counts must be bit-equal again.
constexpr double kHalfUlps = 1.0;

double half_ulp(float cpu) {
    int e = 0;
    std::frexp(static_cast<double>(cpu), &e);  // |cpu| in [2^(e - 1), 2^e)
    return std::ldexp(1.0, (cpu == 0.0f ? -14 : std::max(e - 1, -14)) - 10);
}

/// A method: its define in the passes and its estimator in the C++ policy; its state type picks the history layout
/// (emcv::port::EmcvEmcm2: cv's emcm2 layout; EmcvMovingStats: the moving-statistics layout).
struct Method {
    const char* name;
    const char* define;
    emcv::sampling_estimator estimator;
};

/// What one method's run saw: its fewest and most samples, and (moving layout) its largest texel error as a
/// fraction of the bound.
struct Seen {
    int n_min = 0, n_max = 0;
    double worst = 0.0;
};

/// One method's 60 frames on the GPU against the C++ policy: 0 when they agree, else 1 after printing why.
template <class State>
int run(const Method& method, const std::vector<fs::path>& roots, Seen& seen) {
    constexpr bool emcm2 = std::is_same_v<State, emcv::port::EmcvEmcm2>;  // else the moving-statistics layout
    CONSUMER_GL(PFNGLUSEPROGRAMPROC, glUseProgram);
    CONSUMER_GL(PFNGLDELETEPROGRAMPROC, glDeleteProgram);
    CONSUMER_GL(PFNGLCREATEBUFFERSPROC, glCreateBuffers);
    CONSUMER_GL(PFNGLDELETEBUFFERSPROC, glDeleteBuffers);
    CONSUMER_GL(PFNGLNAMEDBUFFERSTORAGEPROC, glNamedBufferStorage);
    CONSUMER_GL(PFNGLNAMEDBUFFERSUBDATAPROC, glNamedBufferSubData);
    CONSUMER_GL(PFNGLBINDBUFFERBASEPROC, glBindBufferBase);
    CONSUMER_GL(PFNGLCREATETEXTURESPROC, glCreateTextures);
    CONSUMER_GL(PFNGLDELETETEXTURESPROC, glDeleteTextures);
    CONSUMER_GL(PFNGLTEXTURESTORAGE2DPROC, glTextureStorage2D);
    CONSUMER_GL(PFNGLTEXTURESUBIMAGE2DPROC, glTextureSubImage2D);
    CONSUMER_GL(PFNGLGETTEXTUREIMAGEPROC, glGetTextureImage);
    CONSUMER_GL(PFNGLTEXTUREPARAMETERIPROC, glTextureParameteri);
    CONSUMER_GL(PFNGLBINDTEXTUREUNITPROC, glBindTextureUnit);
    CONSUMER_GL(PFNGLBINDIMAGETEXTUREPROC, glBindImageTexture);
    CONSUMER_GL(PFNGLDISPATCHCOMPUTEPROC, glDispatchCompute);
    CONSUMER_GL(PFNGLMEMORYBARRIERPROC, glMemoryBarrier);

    // The four passes: #version, the method and the budget, then the pass with its includes resolved.
    const std::string prelude = std::string("#version 450 core\n#define ") + method.define +
                                " 1\n#define EMCV_HISTORY_SPP_BUDGET " + std::to_string(kBudget) + "f\n";
    const fs::path here = fs::path(CONSUMER_DIR);
    GLuint programs[4] = {};
    const char* const names[4] = {"plan", "solve", "count", "update"};
    for (int k = 0; k < 4; ++k) {
        std::string source;
        try {
            source = prelude + resolve(here / (std::string(names[k]) + ".comp.glsl"), roots);
        } catch (const std::exception& e) {
            std::printf("FAILED: %s\n", e.what());
            return 1;
        }
        programs[k] = consumer::compile_compute(source, std::string(names[k]) + ".comp.glsl");
        if (programs[k] == 0) return 1;
    }

    // Resources, at app.glsl's bindings, in the layout's formats (EMCV_ADAPTIVE_HISTORY_FORMAT_A, _B; texel B for
    // cv only, EMCV_ADAPTIVE_HISTORY_TEXELS). The histories start cleared to zero, which decodes as the fresh state.
    std::vector<State> states(kPixels);
    if constexpr (emcm2)
        states.assign(kPixels, emcv::port::emcv_emcm2_init());
    else
        states.assign(kPixels, emcv::port::emcv_moving_stats_init());
    const int texels = emcm2 ? 2 : 1;
    const GLenum format_a = emcm2 ? GL_RGBA32F : GL_RGBA16F;
    const std::vector<float> fresh_a(4 * kPixels, 0.0f), fresh_b(2 * kPixels, 0.0f);
    GLuint history_a[2], history_b[2] = {}, plan, taken, material, tracked;
    glCreateTextures(GL_TEXTURE_2D, 2, history_a);
    if (texels == 2) glCreateTextures(GL_TEXTURE_2D, 2, history_b);
    for (int k = 0; k < 2; ++k) {
        glTextureStorage2D(history_a[k], 1, format_a, kWidth, kHeight);
        glTextureSubImage2D(history_a[k], 0, 0, 0, kWidth, kHeight, GL_RGBA, GL_FLOAT, fresh_a.data());
        if (texels == 2) {
            glTextureStorage2D(history_b[k], 1, GL_RG32F, kWidth, kHeight);
            glTextureSubImage2D(history_b[k], 0, 0, 0, kWidth, kHeight, GL_RG, GL_FLOAT, fresh_b.data());
        }
    }
    std::vector<std::uint32_t> materials(kPixels), zeros(kPixels, 0u);
    std::vector<std::uint8_t> sub_pixel(kPixels);
    for (int i = 0; i < kPixels; ++i) {
        materials[i] = material_of(i % kWidth, i / kWidth);
        sub_pixel[i] = i % kWidth == kWidth - 1 ? 1 : 0;  // app.glsl's app_sub_pixel (spvg ignores it)
    }
    const auto make_uint = [&](GLuint& t, const std::uint32_t* data) {
        glCreateTextures(GL_TEXTURE_2D, 1, &t);
        glTextureStorage2D(t, 1, GL_R32UI, kWidth, kHeight);
        glTextureSubImage2D(t, 0, 0, 0, kWidth, kHeight, GL_RED_INTEGER, GL_UNSIGNED_INT, data);
    };
    make_uint(plan, zeros.data());
    make_uint(taken, zeros.data());
    make_uint(material, materials.data());
    // texelFetch only, but an integer texture with the default linear filters is incomplete (reads 0)
    glTextureParameteri(material, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(material, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glCreateTextures(GL_TEXTURE_2D, 1, &tracked);
    glTextureStorage2D(tracked, 1, GL_RG32F, kWidth, kHeight);
    GLuint buffers[2];
    glCreateBuffers(2, buffers);
    const emcv::port::host::EmcvBudgetBlock zero_block{};
    glNamedBufferStorage(buffers[0], sizeof zero_block, &zero_block, GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferStorage(buffers[1], 4 * sizeof(std::uint32_t), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
    glBindBufferBase(GL_UNIFORM_BUFFER, 1, buffers[1]);
    glBindImageTexture(4, plan, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindImageTexture(5, taken, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindTextureUnit(8, material);
    glBindTextureUnit(9, tracked);
    const GLbitfield all_barriers = GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                                    GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT;
    const GLuint groups_x = (kWidth + 7) / 8, groups_y = (kHeight + 7) / 8;

    // The C++ library's recipe on the same frames.
    emcv::sampling_params params;
    params.estimator = method.estimator;
    params.mode = emcv::sampling_mode::budget;
    params.budget = kBudget;
    emcv::budget_prior prior;
    std::vector<float> sigma2(kPixels), f(kPixels), g(kPixels), fg(2 * kPixels);
    std::vector<int> counts(kPixels);
    std::vector<std::uint32_t> gpu_counts(kPixels);
    std::vector<float> gpu_a(4 * kPixels), gpu_b(2 * kPixels);
    int failures = 0;
    double left_before = 0, right_before = 0;  // mean N over the last frame before the switch
    std::set<int> distinct;
    for (int t = 0; t < kFrames && failures == 0; ++t) {
        const int now = t % 2, last = 1 - now;
        const std::uint32_t frame[4] = {static_cast<std::uint32_t>(t), kSeed, kWidth, kHeight};
        glNamedBufferSubData(buffers[1], 0, sizeof frame, frame);
        glBindImageTexture(2, history_a[now], 0, GL_FALSE, 0, GL_READ_WRITE, format_a);
        glBindTextureUnit(6, history_a[last]);
        if (texels == 2) {
            glBindImageTexture(3, history_b[now], 0, GL_FALSE, 0, GL_READ_WRITE, GL_RG32F);
            glBindTextureUnit(7, history_b[last]);
        }
        glUseProgram(programs[0]);
        glDispatchCompute(groups_x, groups_y, 1);
        glMemoryBarrier(all_barriers);
        glUseProgram(programs[1]);
        glDispatchCompute(1, 1, 1);
        glMemoryBarrier(all_barriers);
        glUseProgram(programs[2]);
        glDispatchCompute(groups_x, groups_y, 1);
        glMemoryBarrier(all_barriers);
        glGetTextureImage(taken, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, kPixels * 4, gpu_counts.data());

        const emcv::frame_plan cpu = emcv::plan_frame(params, states.data(), kPixels, kWidth, materials.data(),
                                                      sub_pixel.data(), static_cast<std::uint32_t>(t), kSeed, sigma2.data(),
                                                      counts.data(), prior);
        for (int i = 0; i < kPixels && failures < 10; ++i) {
            if (static_cast<int>(gpu_counts[i]) != counts[i]) {
                std::printf("FAILED: %s, frame %d pixel (%d, %d): the GPU planned N = %u, the C++ policy %d\n",
                            method.name, t, i % kWidth, i / kWidth, gpu_counts[i], counts[i]);
                ++failures;
            }
            distinct.insert(counts[i]);
        }
        if (t == kSwitch - 1) {
            for (int i = 0; i < kPixels; ++i)
                (i % kWidth < kWidth / 2 ? left_before : right_before) += counts[i];
        }
        (void)cpu;

        // The host samples; the GPU and the library push the same f and G.
        for (int i = 0; i < kPixels; ++i) {
            sample(i % kWidth, i / kWidth, t, counts[i], f[i], g[i]);
            fg[2 * i] = f[i];
            fg[2 * i + 1] = g[i];
        }
        glTextureSubImage2D(tracked, 0, 0, 0, kWidth, kHeight, GL_RG, GL_FLOAT, fg.data());
        glMemoryBarrier(all_barriers);
        glUseProgram(programs[3]);
        glDispatchCompute(groups_x, groups_y, 1);
        glMemoryBarrier(all_barriers);
        emcv::sampling_update(params, states.data(), kPixels, kWidth, materials.data(), f.data(), g.data(),
                              counts.data());
        glGetTextureImage(history_a[now], 0, GL_RGBA, GL_FLOAT, kPixels * 16, gpu_a.data());
        if constexpr (emcm2) {
            // cv: fp32 texels, bit for bit
            glGetTextureImage(history_b[now], 0, GL_RG, GL_FLOAT, kPixels * 8, gpu_b.data());
            for (int i = 0; i < kPixels && failures < 10; ++i) {
                const auto a = emcv::port::emcv_history_encode_emcm2_cov(states[i]);
                const auto b = emcv::port::emcv_history_encode_emcm2_means(states[i]);
                if (std::memcmp(&a, &gpu_a[4 * i], 16) != 0 || std::memcmp(&b, &gpu_b[2 * i], 8) != 0) {
                    std::printf("FAILED: cv, frame %d pixel (%d, %d): GPU history (%.9g %.9g %.9g count %.0f; means "
                                "%.9g %.9g), C++ (%.9g %.9g %.9g count %.0f; means %.9g %.9g)\n",
                                t, i % kWidth, i / kWidth, double(gpu_a[4 * i]), double(gpu_a[4 * i + 1]),
                                double(gpu_a[4 * i + 2]), double(gpu_a[4 * i + 3]), double(gpu_b[2 * i]),
                                double(gpu_b[2 * i + 1]), double(a.x), double(a.y), double(a.z), double(a.w),
                                double(b.x), double(b.y));
                    ++failures;
                }
            }
        } else {
            // spvg, cv-notex: binary16 texels within one binary16 ulp of the C++ state's fp32 texel, then the C++
            // states re-synchronised to the GPU's (half_ulp's comment derives both)
            for (int i = 0; i < kPixels && failures < 10; ++i) {
                const emcv::port::vec4 c = emcv::port::emcv_history_encode_stats(states[i]);
                const float* gpu = &gpu_a[4 * i];
                bool ok = gpu[2] == c.z && gpu[3] == c.w;  // the count and 0: exact
                for (int k = 0; k < 2; ++k) {             // the mean and the variance / unit
                    const double error = std::fabs(double(gpu[k]) - double(c[k]));
                    const double bound = kHalfUlps * half_ulp(c[k]);
                    ok = ok && std::fabs(c[k]) <= 65504.0f && std::isfinite(gpu[k]) && error <= bound;
                    if (bound > 0.0) seen.worst = std::max(seen.worst, error / bound);
                }
                if (!ok) {
                    std::printf("FAILED: %s, frame %d pixel (%d, %d): GPU history (mean %.9g, variance %.9g units, "
                                "count %.0f, %.9g), C++ (%.9g, %.9g, %.0f, %.9g): beyond one binary16 ulp\n",
                                method.name, t, i % kWidth, i / kWidth, double(gpu[0]), double(gpu[1]),
                                double(gpu[2]), double(gpu[3]), double(c.x), double(c.y), double(c.z), double(c.w));
                    ++failures;
                }
            }
            for (int i = 0; i < kPixels; ++i)
                emcv::port::emcv_history_decode_stats(
                    emcv::port::vec4(gpu_a[4 * i], gpu_a[4 * i + 1], gpu_a[4 * i + 2], gpu_a[4 * i + 3]), states[i]);
        }
    }
    // The sequence must exercise the policy: counts that follow the noise (the right half is noisier).
    if (failures == 0 && !(right_before > 1.5 * left_before && distinct.size() >= 4)) {
        std::printf("FAILED: %s: the counts do not follow the noise (left half %.0f, right half %.0f samples; %zu "
                    "distinct counts)\n", method.name, left_before, right_before, distinct.size());
        ++failures;
    }
    if (!distinct.empty()) {
        seen.n_min = *distinct.begin();
        seen.n_max = *distinct.rbegin();
    }
    glDeleteTextures(2, history_a);
    if (texels == 2) glDeleteTextures(2, history_b);
    const GLuint others[4] = {plan, taken, material, tracked};
    glDeleteTextures(4, others);
    glDeleteBuffers(2, buffers);
    for (const GLuint program : programs) glDeleteProgram(program);
    return failures != 0 ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::printf("usage: budget_consumer <prefix>/share/emcv <prefix>/include\n");
        return 2;
    }
    const std::vector<fs::path> roots{argv[1], argv[2]};
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    if (const int status = consumer::start(display, context); status != 0) return status;
    const Method cv{"cv", "EMCV_ADAPTIVE_CV", emcv::sampling_estimator::cv};
    const Method spvg{"spvg", "EMCV_ADAPTIVE_SPVG", emcv::sampling_estimator::spvg};
    const Method notex{"cv-notex", "EMCV_ADAPTIVE_NOTEX", emcv::sampling_estimator::cv_notex};
    Seen seen[3];
    int status = run<emcv::port::EmcvEmcm2>(cv, roots, seen[0]);  // each method runs, whatever the others did
    status |= run<emcv::port::EmcvMovingStats>(spvg, roots, seen[1]);
    status |= run<emcv::port::EmcvMovingStats>(notex, roots, seen[2]);
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display, context);
    eglTerminate(display);
    if (status != 0) return 1;
    std::printf("budget consumer: OK (%d frames of %dx%d, a light switch at frame %d: counts bit-equal to the C++ "
                "policy, cv's histories too (N from %d to %d), spvg's and cv-notex's binary16 texels within %.4g and "
                "%.4g binary16 ulp (N from %d to %d, %d to %d))\n",
                kFrames, kWidth, kHeight, kSwitch, seen[0].n_min, seen[0].n_max, seen[1].worst, seen[2].worst,
                seen[1].n_min, seen[1].n_max, seen[2].n_min, seen[2].n_max);
    return 0;
}
