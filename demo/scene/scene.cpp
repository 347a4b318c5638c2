// SPDX-License-Identifier: MIT
#include "scene.hpp"

#include <algorithm>

namespace emcv::demo {

bool scene::has_sss_material() const {
    return std::any_of(objects.begin(), objects.end(), [this](const object& o) {
        return o.material >= 0 && static_cast<std::size_t>(o.material) < materials.size() &&
               materials[static_cast<std::size_t>(o.material)].scatters();
    });
}

}  // namespace emcv::demo
