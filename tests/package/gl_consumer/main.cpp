// SPDX-License-Identifier: MIT
// An OpenGL engine taking the installed emcv as it is: no include resolver, no emcv GL code. It creates its own
// headless EGL context (GL 4.5 core), compiles `#version 450 core` + <prefix>/share/emcv/emcv_port.glsl +
// stream.h + a main as one compute shader, runs the per-pixel kernel of stream.h over kPixels pixels, reads
// the states back through <emcv/port/host.hpp>'s std430 mirrors and compares them with the same kernel on the
// CPU (the installed <emcv/port/*.h>, built with -ffp-contract=off): bit for bit (docs/porting.md, parity).
// Exit 0 and "gl consumer: OK" on success, 1 on a failure, 77 (CTest's SKIP_RETURN_CODE) when there is no EGL
// display, unless EMCV_REQUIRE_GL=1 makes that a failure.
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <emcv/port/bindings.h>
#include <emcv/port/host.hpp>

#include "../common/egl_headless.h"
#include "stream.h"

namespace {

constexpr GLuint kPixels = 256;  // four workgroups of EMCV_WORKGROUP_SIZE_X
constexpr GLuint kUpdates = 200;

std::string read_text(const char* path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

const char* const kMain = R"(
layout(local_size_x = EMCV_WORKGROUP_SIZE_X) in;
layout(std430, EMCV_LAYOUT_BINDING(0)) writeonly buffer Covariance { EmcvEmcm2 covariance[]; };
layout(std430, EMCV_LAYOUT_BINDING(1)) writeonly buffer Residual { EmcvMovingStats residual[]; };
layout(std430, EMCV_LAYOUT_BINDING(2)) writeonly buffer Count { int sample_count[]; };
uniform uint updates;  // location 0 set below; the one loose uniform of this test, not of the port
void main() {
    uint pixel = gl_GlobalInvocationID.x;
    EmcvEmcm2 cov;
    EmcvMovingStats res;
    int n;
    consumer_pixel(pixel, updates, cov, res, n);
    covariance[pixel] = cov;
    residual[pixel] = res;
    sample_count[pixel] = n;
}
)";

template <class T>
bool same_bits(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

}  // namespace

int main() {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    if (const int status = consumer::start(display, context); status != 0) return status;

    CONSUMER_GL(PFNGLGETSTRINGPROC, glGetString);
    CONSUMER_GL(PFNGLGETPROGRAMRESOURCEINDEXPROC, glGetProgramResourceIndex);
    CONSUMER_GL(PFNGLGETPROGRAMRESOURCEIVPROC, glGetProgramResourceiv);
    CONSUMER_GL(PFNGLGETUNIFORMLOCATIONPROC, glGetUniformLocation);
    CONSUMER_GL(PFNGLPROGRAMUNIFORM1UIPROC, glProgramUniform1ui);
    CONSUMER_GL(PFNGLUSEPROGRAMPROC, glUseProgram);
    CONSUMER_GL(PFNGLCREATEBUFFERSPROC, glCreateBuffers);
    CONSUMER_GL(PFNGLNAMEDBUFFERSTORAGEPROC, glNamedBufferStorage);
    CONSUMER_GL(PFNGLBINDBUFFERBASEPROC, glBindBufferBase);
    CONSUMER_GL(PFNGLDISPATCHCOMPUTEPROC, glDispatchCompute);
    CONSUMER_GL(PFNGLMEMORYBARRIERPROC, glMemoryBarrier);
    CONSUMER_GL(PFNGLGETNAMEDBUFFERSUBDATAPROC, glGetNamedBufferSubData);
    CONSUMER_GL(PFNGLDELETEBUFFERSPROC, glDeleteBuffers);
    CONSUMER_GL(PFNGLDELETEPROGRAMPROC, glDeleteProgram);
    std::printf("GL_RENDERER: %s\n", reinterpret_cast<const char*>(glGetString(GL_RENDERER)));

    // The shader: #version, the installed flattened port, the kernel, main. No include resolver.
    const std::string source = "#version 450 core\n" + read_text(EMCV_PORT_GLSL) + "\n" + read_text(CONSUMER_STREAM) + kMain;
    const GLuint program = consumer::compile_compute(source, "the compute shader");
    if (program == 0) return 1;
    int failures = 0;

    // The driver's std430 layout of EmcvEmcm2 is host.hpp's.
    const struct { const char* name; std::size_t offset; } members[] = {
        {"covariance[0].mean", offsetof(emcv::port::host::EmcvEmcm2, mean)},
        {"covariance[0].cov", offsetof(emcv::port::host::EmcvEmcm2, cov)},
        {"covariance[0].count", offsetof(emcv::port::host::EmcvEmcm2, count)},
        {"covariance[0].rejected", offsetof(emcv::port::host::EmcvEmcm2, rejected)},
        {"covariance[0].reseeded", offsetof(emcv::port::host::EmcvEmcm2, reseeded)}};
    for (const auto& m : members) {
        const GLuint index = glGetProgramResourceIndex(program, GL_BUFFER_VARIABLE, m.name);
        const GLenum props[] = {GL_OFFSET, GL_TOP_LEVEL_ARRAY_STRIDE};
        GLint values[2] = {-1, -1};
        glGetProgramResourceiv(program, GL_BUFFER_VARIABLE, index, 2, props, 2, nullptr, values);
        if (values[0] != static_cast<GLint>(m.offset) || values[1] != static_cast<GLint>(sizeof(emcv::port::host::EmcvEmcm2))) {
            std::printf("FAILED: %s at offset %d, stride %d in the driver; host.hpp: %zu, %zu\n", m.name, values[0],
                        values[1], m.offset, sizeof(emcv::port::host::EmcvEmcm2));
            ++failures;
        }
    }

    GLuint buffers[3] = {};
    glCreateBuffers(3, buffers);
    const GLsizeiptr sizes[3] = {static_cast<GLsizeiptr>(kPixels * sizeof(emcv::port::host::EmcvEmcm2)),
                                 static_cast<GLsizeiptr>(kPixels * sizeof(emcv::port::host::EmcvMovingStats)),
                                 static_cast<GLsizeiptr>(kPixels * sizeof(GLint))};
    for (GLuint b = 0; b < 3; ++b) {
        glNamedBufferStorage(buffers[b], sizes[b], nullptr, GL_DYNAMIC_STORAGE_BIT);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, buffers[b]);
    }
    glProgramUniform1ui(program, glGetUniformLocation(program, "updates"), kUpdates);
    glUseProgram(program);
    glDispatchCompute(kPixels / EMCV_WORKGROUP_SIZE_X, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<emcv::port::host::EmcvEmcm2> gpu_cov(kPixels);
    std::vector<emcv::port::host::EmcvMovingStats> gpu_res(kPixels);
    std::vector<GLint> gpu_count(kPixels);
    glGetNamedBufferSubData(buffers[0], 0, sizes[0], gpu_cov.data());
    glGetNamedBufferSubData(buffers[1], 0, sizes[1], gpu_res.data());
    glGetNamedBufferSubData(buffers[2], 0, sizes[2], gpu_count.data());

    // The same kernel on the CPU, compared bit for bit through the host mirrors.
    std::set<int> counts;
    for (GLuint pixel = 0; pixel < kPixels && failures < 10; ++pixel) {
        EmcvEmcm2 cov;
        EmcvMovingStats res;
        int count = 0;
        consumer_pixel(pixel, kUpdates, cov, res, count);
        const EmcvEmcm2 gpu = emcv::port::host::to_port(gpu_cov[pixel]);
        const bool cov_ok = same_bits(gpu.mean, cov.mean) && same_bits(gpu.cov, cov.cov) && gpu.count == cov.count &&
                            gpu.rejected == cov.rejected && gpu.reseeded == cov.reseeded;
        const bool res_ok = same_bits(gpu_res[pixel], res);
        if (!cov_ok || !res_ok || gpu_count[pixel] != count) {
            std::printf("FAILED: pixel %u: GPU cov (%.9g %.9g %.9g) count %u, residual var %.9g, N %d; "
                        "CPU cov (%.9g %.9g %.9g) count %u, residual var %.9g, N %d\n",
                        pixel, double(gpu.cov.x), double(gpu.cov.y), double(gpu.cov.z), gpu.count,
                        double(gpu_res[pixel].variance), gpu_count[pixel], double(cov.cov.x), double(cov.cov.y),
                        double(cov.cov.z), cov.count, double(res.variance), count);
            ++failures;
        }
        counts.insert(count);
        if (cov.count != kUpdates) ++failures;  // every sample of the stream is finite
    }
    if (counts.size() < 3) {
        std::printf("FAILED: %zu distinct sample counts: the streams do not exercise the control variate\n",
                    counts.size());
        ++failures;
    }

    glDeleteBuffers(3, buffers);
    glDeleteProgram(program);
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display, context);
    eglTerminate(display);
    if (failures != 0) return 1;
    std::printf("gl consumer: OK (%u pixels x %u updates bit-equal to the CPU, sample counts %d to %d)\n", kPixels,
                kUpdates, *counts.begin(), *counts.rbegin());
    return 0;
}
