// SPDX-License-Identifier: MIT
#include "targets.hpp"

namespace emcv::demo {

gl::texture_2d make_target(GLenum format, int width, int height) {
    gl::texture_2d t = gl::texture_2d::create();
    glTextureStorage2D(t.id(), 1, format, width, height);
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}

gl::texture_2d make_cleared_target(GLenum format, int width, int height) {
    gl::texture_2d t = make_target(format, width, height);
    const bool integer = format == GL_R8UI || format == GL_R32UI;
    glClearTexImage(t.id(), 0, integer ? GL_RED_INTEGER : GL_RED, integer ? GL_UNSIGNED_INT : GL_FLOAT, nullptr);
    return t;
}

}  // namespace emcv::demo
