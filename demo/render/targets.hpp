// SPDX-License-Identifier: MIT
// Render targets and history textures: one way to make them, for the frame's passes and the adaptive histories.
#pragma once

#include "gl/handles.hpp"

namespace emcv::demo {

/// A single-level 2-D texture for a render target, nearest filtering and clamped (texelFetch and the image
/// units need a complete texture, and no pass filters a target).
gl::texture_2d make_target(GLenum format, int width, int height);

/// make_target, cleared to zero (integer formats R8UI and R32UI through GL_RED_INTEGER): a history that starts
/// empty, whose zero texels read as "no history".
gl::texture_2d make_cleared_target(GLenum format, int width, int height);

}  // namespace emcv::demo
