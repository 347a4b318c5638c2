// SPDX-License-Identifier: MIT
// Camera path over frames (scene.hpp, camera): linear between keyframes, held outside them.
#include "scene.hpp"

#include <algorithm>

namespace emcv::demo {

std::pair<glm::vec3, glm::vec3> camera::at(int frame) const {
    if (keys.empty()) return {position, target};
    if (frame <= keys.front().frame) return {keys.front().position, keys.front().target};
    if (frame >= keys.back().frame) return {keys.back().position, keys.back().target};
    // First key strictly after `frame`; the one before it is at or before `frame`.
    const auto next = std::upper_bound(keys.begin(), keys.end(), frame,
                                       [](int f, const key& k) { return f < k.frame; });
    const auto prev = next - 1;
    const float t = static_cast<float>(frame - prev->frame) / static_cast<float>(next->frame - prev->frame);
    return {glm::mix(prev->position, next->position, t), glm::mix(prev->target, next->target, t)};
}

bool camera::is_static() const {
    if (keys.size() < 2) return true;
    return std::all_of(keys.begin() + 1, keys.end(), [&](const key& k) {
        return k.position == keys.front().position && k.target == keys.front().target;
    });
}

}  // namespace emcv::demo
