// SPDX-License-Identifier: MIT
// The OSMesa platform through gl.hpp's loader: a GL 4.5 core context from libOSMesa (dlopen()ed), reached by
// direct-state-access calls and a compute dispatch whose result is read back. libOSMesa exports no DSA
// symbols (Mesa 22.3), so this only works when every entry point comes from OSMesaGetProcAddress. Skipped,
// with the reason, where libOSMesa is absent (Mesa >= 25.1) or the build has no OSMesa header.
#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <optional>
#include <vector>

#include "gl/context.hpp"
#include "gl/debug.hpp"
#include "gl/handles.hpp"
#include "gl/program.hpp"

namespace {

emcv::gl::context osmesa_context_or_skip() {
    if (!emcv::gl::platform_built(emcv::gl::platform::osmesa))
        SKIP("skipped: built without the OSMesa platform (no GL/osmesa.h at configure time)");
    emcv::gl::context_options o;
    o.platforms = {emcv::gl::platform::osmesa};
    std::optional<emcv::gl::context> c;
    try {
        c.emplace(o);
    } catch (const emcv::gl::context_error& e) {
        if (e.no_display()) SKIP("skipped: " << e.what());  // libOSMesa itself is missing
        FAIL(e.what());
    }
    return std::move(*c);
}

}  // namespace

TEST_CASE("OSMesa: a GL 4.5 core context that direct-state-access calls reach") {
    auto ctx = osmesa_context_or_skip();
    CHECK(ctx.used_platform() == emcv::gl::platform::osmesa);
    CHECK_THAT(ctx.version(), Catch::Matchers::StartsWith("4.5"));
    emcv::gl::debug_messenger debug;
    auto b = emcv::gl::buffer::create();
    REQUIRE(b.id() != 0u);
    const std::vector<GLuint> in{7u, 11u, 13u};
    glNamedBufferStorage(b.id(), static_cast<GLsizeiptr>(in.size() * sizeof(GLuint)), in.data(), 0);
    std::vector<GLuint> out(in.size(), 0u);
    glGetNamedBufferSubData(b.id(), 0, static_cast<GLsizeiptr>(out.size() * sizeof(GLuint)), out.data());
    CHECK(out == in);
    CHECK(debug.error_count() == 0);
}

TEST_CASE("OSMesa: a compute dispatch writes a buffer that reads back") {
    auto ctx = osmesa_context_or_skip();
    emcv::gl::debug_messenger debug;
    emcv::gl::preprocessed_source source;
    source.files = {"osmesa_test.comp.glsl"};
    source.text = "#version 450\n"
                  "layout(local_size_x = 8) in;\n"
                  "layout(std430, binding = 0) buffer Out { uint values[]; };\n"
                  "void main() { uint i = gl_GlobalInvocationID.x; values[i] = i * i + 3u; }\n";
    const auto prog = emcv::gl::program::compute(source);
    constexpr GLuint count = 64;
    auto b = emcv::gl::buffer::create();
    glNamedBufferStorage(b.id(), count * sizeof(GLuint), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, b.id());
    prog.use();
    glDispatchCompute(count / 8, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<GLuint> out(count, 0u);
    glGetNamedBufferSubData(b.id(), 0, count * sizeof(GLuint), out.data());
    for (GLuint i = 0; i < count; ++i) CHECK(out[i] == i * i + 3u);
    CHECK(debug.error_count() == 0);
}
