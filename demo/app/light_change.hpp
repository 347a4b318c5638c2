// SPDX-License-Identifier: MIT
// The frame from which the summary compares cv with spvg (the frames after a light switch).
#pragma once

#include <optional>

#include "scene/scene.hpp"

namespace emcv::demo::app {

/// The first frame f in [1, frames) at which some light's intensity curve differs from frame f - 1; empty when
/// every light is constant over the rendered frames.
std::optional<int> first_light_change(const scene& s, int frames);

}  // namespace emcv::demo::app
