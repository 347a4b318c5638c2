// SPDX-License-Identifier: MIT
// What emcv-demo prints without rendering: the built-in scenes (--list-scenes) and a scene's pass list per
// method and frame range (--print-passes). Neither needs a GL context.
#pragma once

#include <ostream>
#include <vector>

#include "render/renderer.hpp"
#include "scene/scene.hpp"

namespace emcv::demo::app {

/// One line per built-in scene: "name  description". A built-in scene that fails to load is listed with
/// its error instead (and makes the function return false).
bool list_scenes(std::ostream& out);

/// One line per row of the method table: the name `--method all` uses (or the bare name), a tab, its SSS
/// passes (none, burley, separable, adaptive), a tab, its help line. Scripts read their method lists here.
void list_methods(std::ostream& out);

/// For each method: "method M:" then one line per run of frames with the same pass list,
/// "  frames A-B: pass, pass, ...", with the temporal resolve as `resolve` asks.
void print_passes(std::ostream& out, const scene& s, const std::vector<method>& methods, int frames, int width,
                  int height, resolve_mode resolve, const sampling_mode& sampling);

}  // namespace emcv::demo::app
