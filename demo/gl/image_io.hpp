// SPDX-License-Identifier: MIT
// Readback of GL textures into float buffers. The image file I/O itself has no GL and lives in
// image/image_file.hpp (values stored unchanged: EXR floats, PNG clamped and quantised to 8 bits, no colour
// transfer); its names are visible here too, so GL code reads a texture and writes it through one header.
#pragma once

#include "gl.hpp"
#include "image/image_file.hpp"

namespace emcv::gl {

using image::float_image;
using image::image_error;
using image::read_image;
using image::write_image;

/// glGetTextureImage of level 0 as GL_RGBA / GL_FLOAT (4 channels).
float_image read_texture_rgba32f(GLuint texture, int width, int height);

}  // namespace emcv::gl
