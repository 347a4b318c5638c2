// SPDX-License-Identifier: MIT
// The frame's pass list, derived from the scene (renderer.hpp): only the passes the scene calls for.
#include "renderer.hpp"
#include "view.hpp"

namespace emcv::demo {

bool sss_possibly_visible(const scene& s, int frame, int width, int height) {
    if (!s.has_sss_material()) return false;
    const view_matrices v = camera_matrices(s.view, frame, width, height);
    for (const object& o : s.objects) {
        if (!s.materials.at(static_cast<std::size_t>(o.material)).scatters()) continue;
        if (sphere_in_frustum(v.view_proj, object_bounds(s, o))) return true;
    }
    return false;
}

bool light_has_shadow_pass(const light& l) {
    return l.casts_shadow && l.type != light::kind::point;
}

bool light_shines(const light& l, int frame) {
    return l.intensity.at(frame) > 0.0f;
}

std::vector<std::string> pass_list(const scene& s, const method& m, int frame, int width, int height) {
    std::vector<std::string> passes{"gbuffer"};
    for (const light& l : s.lights) {
        if (light_has_shadow_pass(l) && light_shines(l, frame)) passes.push_back("shadow:" + l.name);
    }
    passes.emplace_back("lighting");
    if (m.scatters() && sss_possibly_visible(s, frame, width, height)) {
        passes.emplace_back("sss-tiles");
        if (m.type == method::kind::separable) {
            passes.emplace_back("sss-separable-h");
            passes.emplace_back("sss-separable-v");
        } else if (m.type == method::kind::spvg || m.type == method::kind::cv || m.type == method::kind::cv_notex) {
            passes.emplace_back("sss-adaptive-samples");  // N per pixel from the reprojected history
            passes.emplace_back("sss-burley");
            passes.emplace_back("sss-adaptive-update");   // this frame's (f, G) into the history
        } else {
            passes.emplace_back("sss-burley");
        }
    }
    passes.emplace_back("composite");
    return passes;
}

}  // namespace emcv::demo
