// SPDX-License-Identifier: MIT
// Light intensity over frames (scene.hpp, curve).
#include "scene.hpp"

#include <algorithm>
#include <cmath>

#include <emcv/port/port.h>

namespace emcv::demo {
namespace {

constexpr double two_pi = 2.0 * EMCV_PI;

bool in_burst(const curve& c, int frame) {
    return std::any_of(c.bursts.begin(), c.bursts.end(),
                       [&](int start) { return frame >= start && frame - start < c.burst_length; });
}

}  // namespace

float curve::at(int frame) const {
    switch (type) {
    case kind::constant:
        return value;
    case kind::steps: {
        float v = value;
        for (const auto& [from, to] : steps) {
            if (frame < from) break;
            v = to;
        }
        return v;
    }
    case kind::flicker:
        return in_burst(*this, frame) ? peak : value;
    case kind::sinusoid: {
        const double angle = two_pi * static_cast<double>(frame) / static_cast<double>(period_frames) +
                             static_cast<double>(phase);
        const double v = static_cast<double>(value) + static_cast<double>(amplitude) * std::sin(angle);
        return static_cast<float>(std::max(v, 0.0));
    }
    }
    return value;
}

bool curve::is_constant() const {
    switch (type) {
    case kind::constant:
        return true;
    case kind::steps: {
        // The value at frame 0 includes every step at a frame <= 0; a later step that changes it breaks constancy.
        const float start = at(0);
        return std::all_of(steps.begin(), steps.end(),
                           [&](const auto& s) { return s.first <= 0 || s.second == start; });
    }
    case kind::flicker:
        return peak == value || burst_length <= 0 ||
               std::none_of(bursts.begin(), bursts.end(), [&](int start) { return start + burst_length > 0; });
    case kind::sinusoid: {
        if (amplitude == 0.0f || value + std::fabs(amplitude) <= 0.0f) return true;  // flat, or floored at 0
        // Integer frames sample sin(2 pi k frame + phase) at one phase when 1 / period_frames is an integer k.
        const double cycles_per_frame = 1.0 / static_cast<double>(period_frames);
        return cycles_per_frame == std::floor(cycles_per_frame);
    }
    }
    return false;
}

}  // namespace emcv::demo
