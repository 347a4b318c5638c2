// SPDX-License-Identifier: MIT
#include "debug.hpp"

#include <cstdio>
#include <cstring>

#include "gl.hpp"

namespace emcv::gl {
namespace {

void GLAPIENTRY debug_callback(GLenum, GLenum type, GLuint, GLenum severity, GLsizei, const GLchar* message,
                               const void* user) {
    static_cast<debug_messenger*>(const_cast<void*>(user))->on_message(type, severity, message);
}

}  // namespace

debug_messenger::debug_messenger(bool verbose) : verbose_(verbose) {
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
    glDebugMessageCallback(debug_callback, this);
}

debug_messenger::~debug_messenger() { glDebugMessageCallback(nullptr, nullptr); }

void debug_messenger::on_message(unsigned type, unsigned severity, const char* message) {
    if (type == GL_DEBUG_TYPE_ERROR) {
        ++errors_;
        last_error_ = message ? message : "";
        std::fprintf(stderr, "GL error: %s\n", last_error_.c_str());
    } else if (verbose_ && severity != GL_DEBUG_SEVERITY_NOTIFICATION && type != GL_DEBUG_TYPE_PUSH_GROUP &&
               type != GL_DEBUG_TYPE_POP_GROUP) {
        std::fprintf(stderr, "GL debug: %s\n", message ? message : "");
    }
}

debug_group::debug_group(const char* name) {
    glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, static_cast<GLsizei>(std::strlen(name)), name);
}
debug_group::~debug_group() { glPopDebugGroup(); }

}  // namespace emcv::gl
