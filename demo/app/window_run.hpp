// SPDX-License-Identifier: MIT
// --window: the same renderer shown in a GLFW window. Keys (also printed at start):
//   M / N  next / previous method      1..9  toggle light 1..9      H  sample-count heatmap on/off
//   R      restart the sequence        Esc, Q  quit
// Every change is printed on stdout ("frame 3: method diffuse"). $EMCV_DEMO_KEYS="M,H,1" presses keys, one per
// frame after the first, as if typed (the Xvfb test).
// The sequence loops over the scene's frames; --frames N ends the run after N frames (the Xvfb test).
#pragma once

#include <optional>
#include <string>

#include "gl/context.hpp"
#include "options.hpp"
#include "scene/scene.hpp"

namespace emcv::demo::app {

/// The key help printed when the window opens.
std::string window_key_help();

/// Runs the window loop on `ctx`, a GLFW window context (gl::platform::glfw_window), until it closes or `frame_limit` frames were
/// shown. Returns the number of frames shown. Throws std::runtime_error when there is no GLFW window.
int run_window(gl::context& ctx, const scene& s, const options& o, std::optional<int> frame_limit);

}  // namespace emcv::demo::app
