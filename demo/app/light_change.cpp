// SPDX-License-Identifier: MIT
#include "light_change.hpp"

namespace emcv::demo::app {

std::optional<int> first_light_change(const scene& s, int frames) {
    for (int f = 1; f < frames; ++f)
        for (const light& l : s.lights)
            if (l.intensity.at(f) != l.intensity.at(f - 1)) return f;
    return std::nullopt;
}

}  // namespace emcv::demo::app
