// SPDX-License-Identifier: MIT
#include "image_io.hpp"

namespace emcv::gl {

float_image read_texture_rgba32f(GLuint texture, int width, int height) {
    float_image img;
    img.width = width;
    img.height = height;
    img.channels = 4;
    img.pixels.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4u);
    glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(img.pixels.size() * sizeof(float)),
                      img.pixels.data());
    return img;
}

}  // namespace emcv::gl
