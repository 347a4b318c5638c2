// SPDX-License-Identifier: MIT
// Move-only RAII owners of GL object names, created with direct state access (glCreate*).
#pragma once

#include <utility>

#include "gl.hpp"

namespace emcv::gl {

template <class Traits>
class handle {
public:
    handle() = default;
    /// Takes ownership of an existing name.
    explicit handle(GLuint id) noexcept : id_(id) {}
    static handle create() { return handle(Traits::create()); }
    ~handle() { reset(); }
    handle(handle&& o) noexcept : id_(std::exchange(o.id_, 0u)) {}
    handle& operator=(handle&& o) noexcept {
        if (this != &o) {
            reset();
            id_ = std::exchange(o.id_, 0u);
        }
        return *this;
    }
    handle(const handle&) = delete;
    handle& operator=(const handle&) = delete;

    GLuint id() const noexcept { return id_; }
    explicit operator bool() const noexcept { return id_ != 0u; }
    void reset() noexcept {
        if (id_ != 0u) Traits::destroy(id_);
        id_ = 0u;
    }

private:
    GLuint id_ = 0u;
};

struct buffer_traits {
    static GLuint create() { GLuint id = 0; glCreateBuffers(1, &id); return id; }
    static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct texture_2d_traits {
    static GLuint create() { GLuint id = 0; glCreateTextures(GL_TEXTURE_2D, 1, &id); return id; }
    static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};
struct framebuffer_traits {
    static GLuint create() { GLuint id = 0; glCreateFramebuffers(1, &id); return id; }
    static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct vertex_array_traits {
    static GLuint create() { GLuint id = 0; glCreateVertexArrays(1, &id); return id; }
    static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct query_timestamp_traits {
    static GLuint create() { GLuint id = 0; glCreateQueries(GL_TIMESTAMP, 1, &id); return id; }
    static void destroy(GLuint id) { glDeleteQueries(1, &id); }
};
struct program_traits {
    static GLuint create() { return glCreateProgram(); }
    static void destroy(GLuint id) { glDeleteProgram(id); }
};
struct shader_traits {
    static void destroy(GLuint id) { glDeleteShader(id); }
};

using buffer = handle<buffer_traits>;
using texture_2d = handle<texture_2d_traits>;
using framebuffer = handle<framebuffer_traits>;
using vertex_array = handle<vertex_array_traits>;
using timestamp_query = handle<query_timestamp_traits>;
using program_handle = handle<program_traits>;
using shader_handle = handle<shader_traits>;

}  // namespace emcv::gl
