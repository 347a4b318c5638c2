// SPDX-License-Identifier: MIT
// The adaptive passes (shaders/adaptive through demo/render/adaptive/history) on llvmpipe over a hand-made
// 16x8 G-buffer whose every input the test sets: flat SSS pixels at depth 2, no motion, albedo 1, exposure 1.
//   parity       each frame's stored state equals the port's estimator compiled as C++ (emcv_*_push_batch)
//                restored from last frame's stored state and fed the same f, G and batch size N (varying per
//                pixel and frame, 0 included: no push); the sample count equals the quality-target rule
//                rebuilt from the library's own estimators (emcv::emcm, emcv::moving_stats,
//                emcv::cv_optimal_residual_variance, emcv::sample_count) and the per-sample scaling.
//   disocclusion a pixel whose material, depth or normal changed, or whose motion leads off screen, restarts.
//   resampling   a fractional motion blends the statistics of the 2x2 texels around the previous position
//                (bilinear weights, texels of the same surface and valid state only); the texel it falls in
//                gives the count.
//   poison       a NaN/Inf/negative stored state is refused and restarted, and its neighbours are untouched.
//
// Parity bounds (docs/porting.md): the port's estimator fields are bit-equal between CPU and GPU for equal
// inputs and equal starting states (0 ulp on llvmpipe), so every fp32 field must be equal. A field stored in
// binary16 passes through one rounding on each side (the GPU's image store, glm::packHalf1x16 here): both are
// round-to-nearest of the same fp32 value, allowed to differ by one half ulp where a rounding mode or a tie
// differs; nothing accumulates because each frame starts both sides from the GPU's stored state.
#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <utility>
#include <limits>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>

#include <emcv/control_variate.hpp>
#include <emcv/emcm.hpp>
#include <emcv/moving_stats.hpp>
#include <emcv/adaptive_sampling.hpp>
#include <emcv/port/history.h>
#include <emcv/sample_count.hpp>

#include "../gpu/gl_test_support.hpp"
#include "../support/source_dirs.hpp"
#include "gl/debug.hpp"
#include "gl/handles.hpp"
#include "gl/program.hpp"
#include "render/adaptive/history.hpp"
#include "render/gpu_types.hpp"

using emcv::demo::adaptive::history;
using kind = emcv::demo::method::kind;
using emcv::demo::adaptive::texel;

namespace {

constexpr int width = 16, height = 8;  // two 8x8 SSS tiles
constexpr std::size_t pixels = std::size_t(width) * height;

// Binding slots of shaders/render/bindings.h (the history's passes read them like the renderer's).
constexpr GLuint frame_slot = 0, materials_slot = 2, stats_slot = 4, tiles_slot = 5;
constexpr GLuint tex_depth = 10, tex_normal = 11, tex_albedo = 12, tex_material = 13, tex_diffuse = 14, tex_motion = 17;
constexpr GLuint tex_sss_in = 16, img_count = 1;
// shaders/adaptive/bindings.h: the previous frame's G-buffer, which the renderer ping-pongs with its own.
constexpr GLuint tex_prev_depth = 26, tex_prev_normal = 27, tex_prev_material = 28;

emcv::gl::preprocess_options shader_options() {
    emcv::gl::preprocess_options o;
    o.include_dirs = emcv_test::shader_include_dirs();
    return o;
}

emcv::gl::texture_2d make_texture(GLenum format) {
    emcv::gl::texture_2d t = emcv::gl::texture_2d::create();
    glTextureStorage2D(t.id(), 1, format, width, height);
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

float half(float x) { return glm::unpackHalf1x16(glm::packHalf1x16(x)); }

/// Distance in binary16 ulps (both values representable in half).
int half_ulps(float a, float b) {
    const int ia = glm::packHalf1x16(a), ib = glm::packHalf1x16(b);
    return std::abs(ia - ib);
}

/// The hand-made frame: G-buffer, lighting, scattered output, the renderer's blocks, the probe.
struct harness {
    emcv::gl::texture_2d depth = make_texture(GL_R32F), normal = make_texture(GL_RGBA16F),
                         albedo = make_texture(GL_RGBA16F), material = make_texture(GL_R8UI),
                         motion = make_texture(GL_RG16F), diffuse = make_texture(GL_RGBA16F),
                         scattered = make_texture(GL_RGBA16F), taken = make_texture(GL_R32UI),
                         prev_depth = make_texture(GL_R32F), prev_normal = make_texture(GL_RGBA16F),
                         prev_material = make_texture(GL_R8UI);
    emcv::gl::buffer frame_ubo = emcv::gl::buffer::create(), materials = emcv::gl::buffer::create(),
                     stats = emcv::gl::buffer::create(), tiles = emcv::gl::buffer::create();
    emcv::gl::program probe = emcv::gl::program::compute(
        emcv_test::shader_dir() / "adaptive/tests/gamma_probe.comp.glsl", shader_options());

    std::vector<float> depths = std::vector<float>(pixels, 2.0f);
    std::vector<std::uint8_t> codes = std::vector<std::uint8_t>(pixels, 1);
    std::vector<glm::vec4> normals = std::vector<glm::vec4>(pixels, glm::vec4(0, 0, 1, 0));
    std::vector<glm::vec2> motions = std::vector<glm::vec2>(pixels, glm::vec2(0.0f));

    harness() {
        set_taken(std::vector<std::uint32_t>(pixels, 1u));
        glClearTexImage(prev_material.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);  // no previous frame
        emcv::demo::gpu::frame_block f{};
        f.view = glm::mat4(1.0f);
        f.proj = glm::perspective(glm::radians(60.0f), float(width) / float(height), 0.1f, 100.0f);
        f.view_proj = f.proj;
        f.prev_view_proj = f.proj;  // clip w = view depth: the expected previous depth of a static point
        f.inv_view = glm::mat4(1.0f);
        f.camera_position = glm::vec4(0, 0, 0, 1);
        f.viewport = glm::vec4(width, height, 1.0f / width, 1.0f / height);
        f.projection = glm::vec4(f.proj[0][0], f.proj[1][1], 0.1f, 100.0f);
        f.background = glm::vec4(0, 0, 0, 1.0f);  // exposure 1
        f.sss = glm::ivec4(0, 1, 1, 0);
        glNamedBufferStorage(frame_ubo.id(), sizeof f, &f, 0);
        emcv::demo::gpu::material_block m{};
        m.albedo = glm::vec4(1, 1, 1, 1);  // kind 1 = SSS
        m.mean_free_path = glm::vec4(1, 1, 1, 0);
        glNamedBufferStorage(materials.id(), sizeof m, &m, 0);
        const std::uint32_t zeros[4] = {0, 0, 0, 0};
        glNamedBufferStorage(stats.id(), sizeof zeros, zeros, 0);
        // Indirect dispatch (2, 1, 1), tile count 2 (the header's w), then the two tiles (x | y << 16).
        const std::uint32_t tile_list[6] = {2, 1, 1, 2, 0u | (0u << 16), 1u | (0u << 16)};
        glNamedBufferStorage(tiles.id(), sizeof tile_list, tile_list, 0);
        const std::vector<glm::vec4> ones(pixels, glm::vec4(1.0f));
        glTextureSubImage2D(albedo.id(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, ones.data());
        upload_geometry();
    }

    void upload_geometry() {
        glTextureSubImage2D(depth.id(), 0, 0, 0, width, height, GL_RED, GL_FLOAT, depths.data());
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTextureSubImage2D(material.id(), 0, 0, 0, width, height, GL_RED_INTEGER, GL_UNSIGNED_BYTE, codes.data());
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTextureSubImage2D(normal.id(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, normals.data());
        glTextureSubImage2D(motion.id(), 0, 0, 0, width, height, GL_RG, GL_FLOAT, motions.data());
    }

    /// Grey levels (representable in binary16, so the RGBA16F upload is exact) of G and f per pixel.
    void set_light(const std::vector<float>& g, const std::vector<float>& f) {
        std::vector<glm::vec4> gd(pixels), fd(pixels);
        for (std::size_t i = 0; i < pixels; ++i) {
            gd[i] = glm::vec4(glm::vec3(g[i]), 1.0f);
            fd[i] = glm::vec4(glm::vec3(f[i]), 1.0f);
        }
        glTextureSubImage2D(diffuse.id(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, gd.data());
        glTextureSubImage2D(scattered.id(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, fd.data());
    }

    /// The GPU's tracked value (emcv_gamma_luminance) of each grey level.
    std::vector<float> tracked(const std::vector<float>& grey) {
        std::vector<glm::vec4> in(grey.size());
        for (std::size_t i = 0; i < grey.size(); ++i) in[i] = glm::vec4(glm::vec3(grey[i]), 1.0f);
        emcv::gl::buffer a = emcv::gl::buffer::create(), b = emcv::gl::buffer::create();
        glNamedBufferStorage(a.id(), static_cast<GLsizeiptr>(in.size() * sizeof(glm::vec4)), in.data(), 0);
        glNamedBufferStorage(b.id(), static_cast<GLsizeiptr>(in.size() * sizeof(float)), nullptr, GL_DYNAMIC_STORAGE_BIT);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, a.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, b.id());
        probe.use();
        glDispatchCompute(static_cast<GLuint>((in.size() + 63) / 64), 1, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        std::vector<float> out(in.size());
        glGetNamedBufferSubData(b.id(), 0, static_cast<GLsizeiptr>(out.size() * sizeof(float)), out.data());
        return out;
    }

    /// The samples the burley pass took per pixel (what the history update pushes each value as a batch of).
    void set_taken(const std::vector<std::uint32_t>& n) {
        glTextureSubImage2D(taken.id(), 0, 0, 0, width, height, GL_RED_INTEGER, GL_UNSIGNED_INT, n.data());
    }

    /// The history update that the adaptive burley pass runs after sampling (emcv_adaptive_update), in a probe
    /// fed with the harness's values (scattered, taken) instead of sampled ones; one program per method.
    /// (One program per method and block size: the probe must be built with the history's EMCV_HISTORY_BLOCK.)
    std::map<std::pair<kind, int>, emcv::gl::program> update_probes;
    emcv::gl::program& update_probe(kind k, int block) {
        auto it = update_probes.find({k, block});
        if (it == update_probes.end()) {
            emcv::gl::preprocess_options o = shader_options();
            o.defines.emplace_back("EMCV_HISTORY_BLOCK", std::to_string(block));
            o.defines.emplace_back(std::string(emcv::demo::row_of(emcv::demo::method{k, 0}).adaptive_define()), "1");
            it = update_probes.emplace(std::make_pair(k, block), emcv::gl::program::compute(
                emcv_test::shader_dir() / "adaptive/tests/update_probe.comp.glsl", o)).first;
        }
        return it->second;
    }

    /// One frame of the adaptive passes as the renderer records them: the samples pass (in budget mode followed
    /// by the solve of lambda), then the history update that follows the burley pass's sampling.
    void frame(history& h, kind k, int block = 1) {
        glBindBufferBase(GL_UNIFORM_BUFFER, frame_slot, frame_ubo.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, materials_slot, materials.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, stats_slot, stats.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, tiles_slot, tiles.id());
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, tiles.id());
        glBindTextureUnit(tex_depth, depth.id());
        glBindTextureUnit(tex_normal, normal.id());
        glBindTextureUnit(tex_albedo, albedo.id());
        glBindTextureUnit(tex_material, material.id());
        glBindTextureUnit(tex_motion, motion.id());
        glBindTextureUnit(tex_diffuse, diffuse.id());
        glBindTextureUnit(tex_prev_depth, prev_depth.id());
        glBindTextureUnit(tex_prev_normal, prev_normal.id());
        glBindTextureUnit(tex_prev_material, prev_material.id());
        h.record_samples();
        update_probe(k, block).use();
        h.bind_for_update();
        glBindTextureUnit(tex_sss_in, scattered.id());
        glBindImageTexture(img_count, taken.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
        glDispatchComputeIndirect(0);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
        h.end_frame(true);
        // This frame's G-buffer is the next one's previous (the renderer swaps its targets; the harness copies).
        glCopyImageSubData(depth.id(), GL_TEXTURE_2D, 0, 0, 0, 0, prev_depth.id(), GL_TEXTURE_2D, 0, 0, 0, 0, width, height, 1);
        glCopyImageSubData(normal.id(), GL_TEXTURE_2D, 0, 0, 0, 0, prev_normal.id(), GL_TEXTURE_2D, 0, 0, 0, 0, width, height, 1);
        glCopyImageSubData(material.id(), GL_TEXTURE_2D, 0, 0, 0, 0, prev_material.id(), GL_TEXTURE_2D, 0, 0, 0, 0, width, height, 1);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    }

    std::vector<std::uint32_t> counts(const history& h) const {
        std::vector<std::uint32_t> n(pixels);
        glGetTextureImage(h.samples_texture(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                          static_cast<GLsizei>(n.size() * sizeof(std::uint32_t)), n.data());
        return n;
    }
};

/// Per pixel and frame: a light that switches (x0.25 at frame 6) under a per-pixel, per-frame noise on f, so
/// every estimator field moves; with `unexplained`, from the switch every fourth pixel's f also moves by 64/1024
/// more than G explains (a change for cv-notex's change test). Grey levels on a 1/1024 grid (exact in binary16).
void light_at(int frame, std::vector<float>& g, std::vector<float>& f, bool unexplained = false) {
    g.resize(pixels);
    f.resize(pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
        const float level = frame < 6 ? 1.0f : 0.25f;
        const float base = (256.0f + 4.0f * float(i % 32)) / 1024.0f;
        const int noise = int((i * 7919u + std::size_t(frame) * 104729u) % 41u) - 20;
        g[i] = std::round(level * base * 1024.0f) / 1024.0f;
        f[i] = std::round(level * (0.9f * base + float(noise) / 1024.0f) * 1024.0f) / 1024.0f;
        if (unexplained && frame >= 6 && i % 4u == 0u) f[i] += 64.0f / 1024.0f;
    }
}

/// The per-sample variance rebuilt from the library: the tracked variance (the residual's for cv, from the
/// library's EMCM) unbiased by (2 - eta) / (2 (1 - eta)) (the exponential weights' sum of squares,
/// docs/renderer.md); -1 before two frames.
double cpp_sigma2(std::uint64_t count, float variance, float eta) {
    if (count < 2) return -1.0;
    return double(variance) * (2.0 - double(eta)) / (2.0 * (1.0 - double(eta)));
}

/// The quality-target counts of the test's 16x8 frame (one material): each pixel's variance pooled as the mean
/// over its 3x3 neighbours inside its 8x8 tile that have one, over the target, rounded up and clamped to
/// [N_MIN, N_MAX]; N_MAX without a variance. Written from the rule in docs/renderer.md, not from the port.
std::vector<int> cpp_counts(const std::vector<double>& sigma2) {
    std::vector<int> n(pixels);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const double own = sigma2[std::size_t(y * width + x)];
            if (own < 0.0) {
                n[std::size_t(y * width + x)] = EMCV_HISTORY_N_MAX;
                continue;
            }
            double sum = 0.0;
            int k = 0;
            for (int qy = y - 1; qy <= y + 1; ++qy)
                for (int qx = x - 1; qx <= x + 1; ++qx) {
                    if (qx < 0 || qy < 0 || qx >= width || qy >= height || qx / 8 != x / 8 || qy / 8 != y / 8) continue;
                    const double v = sigma2[std::size_t(qy * width + qx)];
                    if (v >= 0.0) sum += v, ++k;
                }
            const double q = sum / k / double(EMCV_HISTORY_TARGET);
            n[std::size_t(y * width + x)] =
                q >= EMCV_HISTORY_N_MAX ? EMCV_HISTORY_N_MAX : std::max(EMCV_HISTORY_N_MIN, int(std::ceil(q)));
        }
    }
    return n;
}

/// The batch size pixel i takes at `frame`: 0 (no push) to 6, different between neighbours and frames.
std::uint32_t taken_at(std::size_t i, int frame) { return std::uint32_t((i * 3u + std::size_t(frame)) % 7u); }

std::uint32_t bits(float x) {
    std::uint32_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
}

}  // namespace

TEST_CASE("the GPU history equals the C++ estimators fed the same per-pixel values, frame by frame") {
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    harness hx;
    for (const kind k : {kind::spvg, kind::cv, kind::cv_notex}) {
        INFO("method " << (k == kind::spvg ? "spvg" : k == kind::cv ? "cv" : "cv-notex"));
        history h(emcv::demo::method{k, 0}, width, height, shader_options(), emcv_test::shader_dir());
        std::vector<texel> previous(pixels);  // fresh: all zero
        std::vector<float> g, f;
        int compared = 0, noise_rescaled = 0, notex_clipped = 0;
        for (int frame = 0; frame < 12; ++frame) {
            light_at(frame, g, f, k == kind::cv_notex);
            hx.set_light(g, f);
            std::vector<std::uint32_t> taken(pixels);
            for (std::size_t i = 0; i < pixels; ++i) taken[i] = taken_at(i, frame);
            hx.set_taken(taken);
            const std::vector<float> gt = hx.tracked(g), ft = hx.tracked(f);
            hx.frame(h, k);
            const std::vector<texel> now = h.read();
            const std::vector<std::uint32_t> n = hx.counts(h);
            std::vector<double> sigma2(pixels);
            // cv: the whole frame's update by the library's sampling_update (the push, then the tile's noise
            // test), from the same stored states, one material.
            std::vector<emcv::port::EmcvEmcm2> api(pixels);
            if (k == kind::cv) {
                for (std::size_t i = 0; i < pixels; ++i)
                    REQUIRE(emcv::port::emcv_history_decode_emcm2(previous[i].a, previous[i].b, api[i]));
                emcv::sampling_params cvp;
                cvp.estimator = emcv::sampling_estimator::cv;
                std::vector<int> taken_int(taken.begin(), taken.end());
                emcv::sampling_update(cvp, api.data(), pixels, std::size_t(width), nullptr, ft.data(), gt.data(),
                                      taken_int.data());
            }
            for (std::size_t i = 0; i < pixels; ++i) {
                INFO("frame " << frame << " pixel " << i << " batch " << taken[i]);
                const texel& was = previous[i];
                const float batch = float(taken[i]);
                if (batch == 0.0f) {  // no samples, nothing learnt: the state is kept bit for bit (no push)
                    CHECK(bits(now[i].a.x) == bits(was.a.x));
                    CHECK(bits(now[i].a.y) == bits(was.a.y));
                    CHECK(bits(now[i].a.z) == bits(was.a.z));
                    CHECK(bits(now[i].a.w) == bits(was.a.w));
                    CHECK(bits(now[i].b.x) == bits(was.b.x));
                    CHECK(bits(now[i].b.y) == bits(was.b.y));
                }
                if (k == kind::cv) {
                    // The count from the library's EMCM restored from the stored state (the GPU's decode).
                    emcv::emcm<float, 2>::state_type s{};
                    s.count = static_cast<std::uint64_t>(was.a.w);
                    s.total_weight = s.count > 0 ? 1.0f : 0.0f;
                    s.mean = {was.b.x, was.b.y};
                    s.covariance = {was.a.x, was.a.y, was.a.z};
                    const emcv::emcm<float, 2> lib(EMCV_HISTORY_ETA_EMCM, s);
                    sigma2[i] = cpp_sigma2(lib.count(), emcv::cv_optimal_residual_variance(lib), EMCV_HISTORY_ETA_EMCM);
                    // The update: the port's batch push compiled as C++, from the same stored state.
                    emcv::port::EmcvEmcm2 port;
                    REQUIRE(emcv::port::emcv_history_decode_emcm2(was.a, was.b, port));
                    if (batch > 0.0f) emcv::port::emcv_history_push_cv(port, ft[i], gt[i], EMCV_HISTORY_ETA_EMCM, batch);
                    // Where the tile's noise test left the push as it was (the library's update equals the port's
                    // push alone), independently of the port: supp. Eq. 21 with the batch factor (supp. Eq.
                    // 25-27), C_ff' = (1 - eta)(C_ff + eta N d^2), in double; fp32 rounding of a few operations
                    // stays under 1e-5 relative.
                    const bool rescaled = bits(api[i].cov.x) != bits(port.cov.x);
                    if (rescaled) ++noise_rescaled;
                    if (batch > 0.0f && port.count > 1 && !rescaled) {
                        const double d = double(ft[i]) - double(was.b.x), eta = EMCV_HISTORY_ETA_EMCM;
                        const double expect = (1.0 - eta) * (double(was.a.x) + eta * double(batch) * d * d);
                        CHECK(std::fabs(double(now[i].a.x) - expect) <= 1e-5 * expect + 1e-12);
                    }
                    CHECK(bits(now[i].a.x) == bits(api[i].cov.x));
                    CHECK(bits(now[i].a.y) == bits(api[i].cov.y));
                    CHECK(bits(now[i].a.z) == bits(api[i].cov.z));
                    CHECK(now[i].a.w == float(api[i].count));
                    CHECK(bits(now[i].b.x) == bits(api[i].mean.x));  // the means are fp32 (RG32F)
                    CHECK(bits(now[i].b.y) == bits(api[i].mean.y));
                    CHECK(api[i].count == port.count);  // the noise test scales the comoments only
                    // G is constant until the switch: no covariance with G may appear from the means' storage
                    // (RG16F means gave C_GG > 0 and a phantom alpha on a static light).
                    if (frame < 6) CHECK(now[i].a.z == 0.0f);
                    if (frame < 6) CHECK(now[i].a.y == 0.0f);
                } else {
                    emcv::moving_stats<float>::state_type s{};
                    s.count = static_cast<std::uint64_t>(was.a.z);
                    s.total_weight = s.count > 0 ? 1.0f : 0.0f;
                    s.mean = {was.a.x};
                    s.covariance = {was.a.y * emcv::port::emcv_history_variance_unit()};
                    const emcv::moving_stats<float> lib(EMCV_HISTORY_ETA_MOVING, s);
                    sigma2[i] = cpp_sigma2(lib.count(), lib.variance(), EMCV_HISTORY_ETA_MOVING);
                    emcv::port::EmcvMovingStats port;
                    REQUIRE(emcv::port::emcv_history_decode_stats(was.a, port));
                    const float x = k == kind::spvg ? ft[i] : emcv::cv_residual(ft[i], 1.0f, gt[i]);
                    if (batch > 0.0f) {
                        if (k == kind::spvg)
                            emcv::port::emcv_moving_stats_push_batch(port, x, EMCV_HISTORY_ETA_MOVING, batch);
                        else
                            emcv::port::emcv_history_push_notex(port, ft[i], gt[i], EMCV_HISTORY_ETA_MOVING, batch);
                    }
                    const float unit = emcv::port::emcv_history_variance_unit();
                    // Independently of the port: var' = (1 - eta)(var + eta N d^2) (supp. Eq. 21, 25-27) in
                    // double, against the stored binary16 value (relative step 2^-11). cv-notex's change test:
                    // once count * eta >= 1, a move with N d^2 > 25 sigma^2 (sigma^2 the stored variance times
                    // (2 - eta) / (2 (1 - eta))) enters with N = 25 sigma^2 / d^2 and the mean restarts at x.
                    if (batch > 0.0f && port.count > 1) {
                        const double d = double(x) - double(was.a.x), eta = EMCV_HISTORY_ETA_MOVING;
                        const double var = double(was.a.y) * unit, sigma2_was = var * (2.0 - eta) / (2.0 * (1.0 - eta));
                        const bool tested = k == kind::cv_notex && double(was.a.z) * eta >= 1.0 && sigma2_was > 0.0;
                        const double z = tested ? double(batch) * d * d / (25.0 * sigma2_was) : 0.0;
                        double weight = double(batch);
                        if (z > 1.0) {
                            weight = 25.0 * sigma2_was / (d * d);
                            ++notex_clipped;
                            CHECK(half_ulps(now[i].a.x, half(x)) <= 1);  // the mean restarts at this frame's r
                        }
                        const double expect = (1.0 - eta) * (var + eta * weight * d * d);
                        // (a move within 1e-3 of the bound may fall either way in fp32)
                        if (std::fabs(z - 1.0) > 1e-3)
                            CHECK(std::fabs(double(now[i].a.y) * unit - expect) <= 1e-3 * expect + 1e-9);
                    }
                    CHECK(half_ulps(now[i].a.x, half(port.mean)) <= 1);
                    INFO("stored var / unit: GPU " << now[i].a.y << ", C++ " << port.variance / unit);
                    CHECK(half_ulps(now[i].a.y, half(port.variance / unit)) <= 1);
                    CHECK(now[i].a.z == float(port.count));
                }
                ++compared;
            }
            // The counts this frame's stored-before state asked for, pooled (fp32 on the GPU against double
            // here: a quotient within 1e-5 of an integer could round either way, none does in this stream).
            const std::vector<int> expect = cpp_counts(sigma2);
            for (std::size_t i = 0; i < pixels; ++i) {
                INFO("frame " << frame << " pixel " << i << " count: GPU " << n[i] << ", rebuilt " << expect[i]);
                CHECK(int(n[i]) == expect[i]);
            }
            previous = now;
        }
        CHECK(compared == 12 * int(pixels));
        // Pixel 5 took no samples on the frames where (15 + frame) % 7 == 0 (frames 6): 11 pushes in 12 frames.
        // cv's count may also be lowered by a 5-sigma move of f's level (this stream's light switch lowers pixel
        // 5's), so for cv the no-sample frames are checked above: the state kept bit for bit.
        if (k != kind::cv) CHECK(previous[5].a.z == 11.0f);
        // The stream's switch (x0.25 at frame 6) makes the tile's noise fall: the comparison above covers the
        // rescaled comoments too.
        if (k == kind::cv) CHECK(noise_rescaled > 0);
        // cv-notex's stream moves every fourth pixel's f from the switch on by more than G explains: the change
        // test's clipped pushes are covered too.
        INFO("cv-notex pushes clipped by the change test: " << notex_clipped);
        if (k == kind::cv_notex) CHECK(notex_clipped > 0);
    }
    CHECK(messenger.error_count() == 0);
}

TEST_CASE("at K = 2 a block's history is its scattering pixels' mean f and G pushed as a batch of n m: the GPU's equals the port's in C++") {
    // The statistics' grain EMCV_HISTORY_BLOCK = 2: the 16x8 frame is an 8x4 block grid, each 8x8 tile 4x4
    // blocks. Every pixel of a block takes its block's N (as the burley pass does); pixel (0, 0) does not scatter,
    // so block (0, 0) has m = 3 pixels and a batch of 3 n. The reference is written here from the port's
    // functions compiled as C++: the block's means in row order over its scattering pixels that took samples,
    // the batch n m (emcv_history_block_batch), and for cv the noise test pooled over the blocks of each GPU
    // tile, then the push and the rescale. fp32 fields must be equal bit for bit (docs/porting.md), binary16
    // fields within one half ulp (one rounding of the same fp32 value on each side).
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    harness hx;
    hx.codes[0] = 0;
    hx.upload_geometry();
    constexpr int k_block = 2, grid_w = width / k_block, grid_h = height / k_block, tile_blocks = 8 / k_block;
    constexpr std::size_t blocks = std::size_t(grid_w) * grid_h;
    emcv::gl::preprocess_options options = shader_options();
    options.defines.emplace_back("EMCV_HISTORY_BLOCK", "2");
    for (const kind k : {kind::spvg, kind::cv}) {
        INFO("method " << (k == kind::spvg ? "spvg" : "cv"));
        history h(emcv::demo::method{k, 0}, width, height, options, emcv_test::shader_dir());
        REQUIRE(h.grid_width() == grid_w);
        REQUIRE(h.grid_height() == grid_h);
        std::vector<texel> previous(blocks);  // fresh: all zero
        std::vector<float> g, f;
        int pushed = 0, three_pixel_pushes = 0, rescaled_tiles = 0;
        for (int frame = 0; frame < 12; ++frame) {
            light_at(frame, g, f);
            hx.set_light(g, f);
            std::vector<std::uint32_t> taken(pixels), block_n(blocks);
            for (std::size_t b = 0; b < blocks; ++b) block_n[b] = taken_at(b, frame);
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x)
                    taken[std::size_t(y * width + x)] = block_n[std::size_t((y / k_block) * grid_w + x / k_block)];
            hx.set_taken(taken);
            const std::vector<float> gt = hx.tracked(g), ft = hx.tracked(f);
            hx.frame(h, k, k_block);
            const std::vector<texel> now = h.read();
            REQUIRE(now.size() == blocks);
            // Each block's means and batch, then (cv) each GPU tile's noise pool over its blocks.
            std::vector<float> mean_f(blocks, 0.0f), mean_g(blocks, 0.0f), batch(blocks, 0.0f);
            for (int by = 0; by < grid_h; ++by) {
                for (int bx = 0; bx < grid_w; ++bx) {
                    const std::size_t b = std::size_t(by * grid_w + bx);
                    float sum_f = 0.0f, sum_g = 0.0f;
                    std::uint32_t m = 0;
                    for (int dy = 0; dy < k_block; ++dy)
                        for (int dx = 0; dx < k_block; ++dx) {
                            const std::size_t i = std::size_t((by * k_block + dy) * width + bx * k_block + dx);
                            if (hx.codes[i] == 0 || taken[i] == 0) continue;
                            sum_f += ft[i];
                            sum_g += gt[i];
                            ++m;
                        }
                    if (m == 0) continue;
                    mean_f[b] = sum_f / float(m);
                    mean_g[b] = sum_g / float(m);
                    batch[b] = emcv::port::emcv_history_block_batch(block_n[b], m);
                    if (m == 3) ++three_pixel_pushes;
                }
            }
            std::vector<glm::uvec3> pool(2, glm::uvec3(0u));
            std::vector<emcv::port::EmcvEmcm2> cv_state(blocks);
            if (k == kind::cv) {
                for (std::size_t b = 0; b < blocks; ++b) {
                    REQUIRE(emcv::port::emcv_history_decode_emcm2(previous[b].a, previous[b].b, cv_state[b]));
                    const float term = batch[b] > 0.0f ? emcv::port::emcv_history_noise_term(cv_state[b], mean_f[b], mean_g[b],
                                                                                               EMCV_HISTORY_ETA_EMCM, batch[b])
                                                       : emcv::port::emcv_history_no_variance();
                    emcv::port::emcv_history_noise_add(pool[(b % std::size_t(grid_w)) / std::size_t(tile_blocks)], term,
                                                       emcv::port::emcv_history_noise_relative(std::max(batch[b], 1.0f)));
                }
                for (const glm::uvec3& t : pool) rescaled_tiles += emcv::port::emcv_history_noise_ratio(t) < 1.0f ? 1 : 0;
            }
            for (std::size_t b = 0; b < blocks; ++b) {
                INFO("frame " << frame << " block " << b << " batch " << batch[b]);
                if (batch[b] > 0.0f) ++pushed;
                if (k == kind::cv) {
                    emcv::port::EmcvEmcm2 s = cv_state[b];
                    if (batch[b] > 0.0f) {
                        emcv::port::emcv_history_push_cv(s, mean_f[b], mean_g[b], EMCV_HISTORY_ETA_EMCM, batch[b]);
                        emcv::port::emcv_history_rescale_cv(
                            s, emcv::port::emcv_history_noise_ratio(pool[(b % std::size_t(grid_w)) / std::size_t(tile_blocks)]));
                    }
                    CHECK(bits(now[b].a.x) == bits(s.cov.x));
                    CHECK(bits(now[b].a.y) == bits(s.cov.y));
                    CHECK(bits(now[b].a.z) == bits(s.cov.z));
                    CHECK(now[b].a.w == float(s.count));
                    CHECK(bits(now[b].b.x) == bits(s.mean.x));
                    CHECK(bits(now[b].b.y) == bits(s.mean.y));
                } else {
                    emcv::port::EmcvMovingStats s;
                    REQUIRE(emcv::port::emcv_history_decode_stats(previous[b].a, s));
                    if (batch[b] > 0.0f) emcv::port::emcv_moving_stats_push_batch(s, mean_f[b], EMCV_HISTORY_ETA_MOVING, batch[b]);
                    CHECK(half_ulps(now[b].a.x, half(s.mean)) <= 1);
                    CHECK(half_ulps(now[b].a.y, half(s.variance / emcv::port::emcv_history_variance_unit())) <= 1);
                    CHECK(now[b].a.z == float(s.count));
                }
            }
            previous = now;
        }
        CHECK(pushed > 200);                 // most of 12 frames x 32 blocks took samples (taken_at is 0 one frame in 7)
        CHECK(three_pixel_pushes >= 10);     // block (0, 0), whose pixel (0, 0) does not scatter, took part
        if (k == kind::cv) CHECK(rescaled_tiles > 0);  // the switch at frame 6: the noise test acted on a tile
    }
    CHECK(messenger.error_count() == 0);
}

TEST_CASE("disocclusion and off-screen motion restart the history; the rest keeps it") {
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    harness hx;
    history h(emcv::demo::method{kind::cv, 0}, width, height, shader_options(), emcv_test::shader_dir());
    std::vector<float> g, f;
    for (int frame = 0; frame < 4; ++frame) {
        light_at(frame, g, f);
        hx.set_light(g, f);
        hx.frame(h, kind::cv);
    }
    REQUIRE(h.read()[0].a.w == 4.0f);
    // Pixel 1: another material; 2: 20% deeper (a surface behind); 3: normal turned 60 degrees; 4: motion from
    // off screen (came in from the left edge); 5: moved by one pixel from pixel 6 (reprojected, kept).
    hx.codes[1] = 2;  // a second material code: the material table has one entry, so keep it scattering below
    hx.depths[2] = 2.4f;
    hx.normals[3] = glm::vec4(std::sin(1.047f), 0.0f, std::cos(1.047f), 0.0f);
    hx.motions[4] = glm::vec2(8.0f, 0.0f);
    hx.motions[5] = glm::vec2(-1.0f, 0.0f);
    // Material code 2 must scatter too (else the pass skips the pixel): give the table a second SSS entry.
    emcv::demo::gpu::material_block m[2]{};
    m[0].albedo = m[1].albedo = glm::vec4(1, 1, 1, 1);
    m[0].mean_free_path = m[1].mean_free_path = glm::vec4(1, 1, 1, 0);  // kernels of many pixels: not sub-pixel
    hx.materials = emcv::gl::buffer::create();
    glNamedBufferStorage(hx.materials.id(), sizeof m, m, 0);
    hx.upload_geometry();
    light_at(4, g, f);
    hx.set_light(g, f);
    hx.frame(h, kind::cv);
    const std::vector<texel> t = h.read();
    const std::vector<std::uint32_t> n = hx.counts(h);
    for (std::size_t i : {std::size_t(1), std::size_t(2), std::size_t(3), std::size_t(4)}) {
        INFO("pixel " << i);
        CHECK(t[i].a.w == 1.0f);  // restarted: one frame pushed
        CHECK(n[i] == EMCV_HISTORY_N_MAX);
    }
    for (std::size_t i : {std::size_t(0), std::size_t(5), std::size_t(6), std::size_t(20)}) {
        INFO("pixel " << i);
        CHECK(t[i].a.w == 5.0f);  // kept
    }
    CHECK(messenger.error_count() == 0);
}

TEST_CASE("a fractional motion resamples the history bilinearly over the texels of the same surface") {
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    for (const kind k : {kind::spvg, kind::cv}) {
        INFO("method " << (k == kind::spvg ? "spvg" : "cv"));
        harness hx;
        history h(emcv::demo::method{k, 0}, width, height, shader_options(), emcv_test::shader_dir());
        std::vector<float> g, f;
        for (int frame = 0; frame < 4; ++frame) {
            light_at(frame, g, f);
            hx.set_light(g, f);
            hx.frame(h, k);
        }
        std::vector<texel> before = h.read();
        // Texel 22 poisoned: pixel 23's blend must leave it out.
        before[22].a.x = std::numeric_limits<float>::quiet_NaN();
        h.write_previous(before);
        // The previous position is p + 0.5 - motion; the blend weighs the texels around it bilinearly, the texel
        // it falls in decides and gives the count. Pixel 5 (5, 0): previous (6.0, 0.5), texels 5 and 6 at 1/2
        // each, count of 6. Pixel 20 (4, 1): previous (4.75, 2.0), texels 20 and 36 at 3/8, 21 and 37 at 1/8,
        // count of 36. Pixel 23 (7, 1): previous (7.0, 1.5), texels 22 (poisoned) and 23 at 1/2: 23 alone.
        struct expectation {
            std::size_t pixel;
            glm::vec2 motion;
            std::vector<std::pair<std::size_t, float>> texels;
            std::size_t decides;
        };
        const std::vector<expectation> cases = {
            {5, {-0.5f, 0.0f}, {{5, 0.5f}, {6, 0.5f}}, 6},
            {20, {-0.25f, -0.5f}, {{20, 0.375f}, {21, 0.125f}, {36, 0.375f}, {37, 0.125f}}, 36},
            {23, {0.5f, 0.0f}, {{23, 0.5f}}, 23},
        };
        // No samples taken at the three pixels: their stored state is the reprojected one, unpushed.
        std::vector<std::uint32_t> taken(pixels, 1u);
        for (const expectation& c : cases) {
            hx.motions[c.pixel] = c.motion;
            taken[c.pixel] = 0u;
        }
        hx.upload_geometry();
        hx.set_taken(taken);
        light_at(4, g, f);
        hx.set_light(g, f);
        hx.frame(h, k);
        const std::vector<texel> after = h.read();
        for (const expectation& c : cases) {
            INFO("pixel " << c.pixel);
            double weight = 0.0;
            glm::dvec4 a(0.0);
            glm::dvec2 b(0.0);
            for (const auto& [texel_index, w] : c.texels) {
                weight += w;
                a += double(w) * glm::dvec4(before[texel_index].a);
                b += double(w) * glm::dvec2(before[texel_index].b);
            }
            a /= weight;
            b /= weight;
            if (k == kind::cv) {
                // fp32 fields: (C_ff, C_fG, C_GG, count) and (mean_f, mean_G).
                for (int j = 0; j < 3; ++j) CHECK(std::abs(double(after[c.pixel].a[j]) - a[j]) <= 1e-6 * std::abs(a[j]) + 1e-12);
                for (int j = 0; j < 2; ++j) CHECK(std::abs(double(after[c.pixel].b[j]) - b[j]) <= 1e-6 * std::abs(b[j]));
                CHECK(after[c.pixel].a.w == before[c.decides].a.w);
            } else {
                // binary16 fields (mean, variance / unit, count): one rounding of the blend.
                CHECK(half_ulps(after[c.pixel].a.x, half(float(a.x))) <= 1);
                CHECK(half_ulps(after[c.pixel].a.y, half(float(a.y))) <= 1);
                CHECK(after[c.pixel].a.z == before[c.decides].a.z);
            }
        }
    }
    CHECK(messenger.error_count() == 0);
}

TEST_CASE("a poisoned history texel (NaN, Inf, negative variance) is reset and never spreads") {
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    for (const kind k : {kind::spvg, kind::cv}) {
        INFO("method " << (k == kind::spvg ? "spvg" : "cv"));
        harness hx;
        history clean(emcv::demo::method{k, 0}, width, height, shader_options(), emcv_test::shader_dir());
        history poisoned(emcv::demo::method{k, 0}, width, height, shader_options(), emcv_test::shader_dir());
        std::vector<float> g, f;
        for (int frame = 0; frame < 4; ++frame) {
            light_at(frame, g, f);
            hx.set_light(g, f);
            hx.frame(clean, k);
            hx.frame(poisoned, k);
        }
        std::vector<texel> bad = poisoned.read();
        const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
        bad[9].a.x = nan;
        bad[10].a.y = inf;
        if (k == kind::cv) bad[11].b.x = -inf;
        else bad[11].a.y = -1.0f;  // a negative variance
        // The history keeps what read() returned as the state the next frame reprojects from.
        poisoned.write_previous(bad);
        light_at(4, g, f);
        hx.set_light(g, f);
        hx.frame(clean, k);
        hx.frame(poisoned, k);
        const std::vector<texel> c = clean.read(), p = poisoned.read();
        const std::vector<std::uint32_t> nc = hx.counts(clean);
        const std::vector<std::uint32_t> np = hx.counts(poisoned);
        for (std::size_t i = 0; i < pixels; ++i) {
            INFO("pixel " << i);
            CHECK(std::isfinite(p[i].a.x));
            CHECK(std::isfinite(p[i].a.y));
            CHECK(std::isfinite(p[i].a.z));
            CHECK(std::isfinite(p[i].b.x));
            const bool was_poisoned = i >= 9 && i <= 11;
            const float count = k == kind::cv ? p[i].a.w : p[i].a.z;
            if (was_poisoned) {
                CHECK(count == 1.0f);
                CHECK(np[i] == EMCV_HISTORY_N_MAX);
            } else {
                CHECK(bits(p[i].a.x) == bits(c[i].a.x));  // untouched: as in the clean run
                CHECK(bits(p[i].a.y) == bits(c[i].a.y));
                CHECK(bits(p[i].b.x) == bits(c[i].b.x));
                CHECK(np[i] == nc[i]);
            }
        }
    }
    CHECK(messenger.error_count() == 0);
}

TEST_CASE("only a budget's burley pass plans the next frame or reuses a plan: asked under a quality target, the history refuses by name") {
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    using emcv::demo::burley_variant;
    history quality(emcv::demo::method{kind::cv, 0}, width, height, shader_options(), emcv_test::shader_dir());
    REQUIRE_FALSE(quality.budget_mode());
    CHECK_THROWS_WITH(quality.use_burley(burley_variant::plans_next), Catch::Matchers::ContainsSubstring("only a budget plans"));
    CHECK_THROWS_WITH(quality.use_burley(burley_variant::reuses_plan), Catch::Matchers::ContainsSubstring("only a budget reuses"));
    quality.use_burley(burley_variant::updates);  // the plain program is there
    emcv::gl::preprocess_options options = shader_options();
    options.defines.emplace_back("EMCV_HISTORY_SPP_BUDGET", "4.0f");
    history budget(emcv::demo::method{kind::cv, 0}, width, height, options, emcv_test::shader_dir());
    budget.use_burley(burley_variant::plans_next);  // built on first use
    budget.use_burley(burley_variant::reuses_plan);
    CHECK(messenger.error_count() == 0);
}

TEST_CASE("budget mode: the samples pass shrinks as the library does and the solve after it finds the library's lambda, bit for bit") {
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    harness hx;
    emcv::gl::preprocess_options options = shader_options();
    options.defines.emplace_back("EMCV_HISTORY_SPP_BUDGET", "6.0f");
    history h(emcv::demo::method{kind::spvg, 0}, width, height, options, emcv_test::shader_dir());
    REQUIRE(h.budget_mode());
    std::vector<float> g, f;
    emcv::sampling_params p;
    p.mode = emcv::sampling_mode::budget;
    p.budget = 6.0f;
    emcv::budget_prior prior;  // the library's plan, fed the states the GPU's samples pass reads each frame
    int shrunk_frames = 0;
    for (int frame = 0; frame < 6; ++frame) {
        light_at(frame, g, f);
        hx.set_light(g, f);
        std::vector<std::uint32_t> taken(pixels);
        for (std::size_t i = 0; i < pixels; ++i) taken[i] = 1u + taken_at(i, frame);
        hx.set_taken(taken);
        const std::vector<texel> before = h.read();
        std::vector<emcv::port::EmcvMovingStats> states(pixels);
        for (std::size_t i = 0; i < pixels; ++i) REQUIRE(emcv::port::emcv_history_decode_stats(before[i].a, states[i]));
        const bool shrinks = prior.mean_sigma2 > 0.0f;
        std::vector<float> cpp_sigma2_codes(pixels);
        std::vector<int> cpp_n(pixels);
        emcv::plan_frame(p, states.data(), pixels, std::size_t(width), nullptr, nullptr, std::uint32_t(frame), 0u,
                         cpp_sigma2_codes.data(), cpp_n.data(), prior);
        hx.frame(h, kind::spvg);
        // The GPU's shrunk codes (the samples image) and the prior its solve stored for the next frame: the
        // library's, bit for bit (the same port functions, the moments added in the same order).
        const std::vector<std::uint32_t> stored = hx.counts(h);
        for (std::size_t i = 0; i < pixels; ++i) {
            INFO("frame " << frame << " pixel " << i);
            CHECK(stored[i] == bits(cpp_sigma2_codes[i]));
        }
        const emcv::port::EmcvBudgetBlock block = h.read_budget();
        INFO("frame " << frame << ": prior GPU (" << block.mean_sigma2 << ", " << block.between_variance << "), C++ ("
                      << prior.mean_sigma2 << ", " << prior.between_variance << ")");
        CHECK(bits(block.mean_sigma2) == bits(prior.mean_sigma2));
        CHECK(bits(block.between_variance) == bits(prior.between_variance));
        if (shrinks) ++shrunk_frames;
    }
    CHECK(shrunk_frames >= 2);  // frames 3 on read a prior (variances from frame 2): the shrinkage was exercised
    CHECK(prior.mean_sigma2 > 0.0f);
    // The variances the last frame's samples pass stored in the samples image, added to a histogram by the
    // library, solved by the library: the same lambda, bit for bit, as the solve pass solved from the
    // histogram the GPU's atomics built (a different pairing of the tree's sums, a lost or doubled pixel, or
    // a bin read before every workgroup had added to it would move it).
    const emcv::port::EmcvBudgetBlock solved = h.read_budget();
    std::vector<std::uint32_t> stored = hx.counts(h);
    emcv::budget_histogram cpp = emcv::make_budget_histogram();
    for (std::uint32_t bits_of_sigma2 : stored) {
        float sigma2;
        std::memcpy(&sigma2, &bits_of_sigma2, sizeof sigma2);
        emcv::budget_add(cpp, sigma2);
    }
    std::uint32_t histogram_pixels = 0;
    for (int b = 0; b < EMCV_BUDGET_BINS; ++b) histogram_pixels += cpp.bin_count[b];
    CHECK(histogram_pixels == pixels);  // five frames of history: every pixel has a variance
    const float lambda = emcv::budget_solve(p, cpp);
    INFO("lambda: GPU " << solved.lambda << ", C++ " << lambda);
    CHECK(bits(solved.lambda) == bits(lambda));
    CHECK(solved.planned == 6.0f * float(pixels));
    // The solve leaves the histogram and its counters empty for the next frame.
    for (int b = 0; b < EMCV_BUDGET_BINS; ++b) {
        CHECK(solved.bin_count[b] == 0u);
        CHECK(solved.bin_fraction[b] == 0u);
        CHECK(solved.raw_count[b] == 0u);
    }
    CHECK(solved.raw_inverse_frames == 0u);
    CHECK(solved.solves == 6u);  // one solve a frame: each frame's samples pass was followed by its solve, once
    CHECK(solved.default_pixels == 0u);
    CHECK(solved.zero_pixels == 0u);
    CHECK(messenger.error_count() == 0);
}
