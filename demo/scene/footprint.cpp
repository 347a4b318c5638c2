// SPDX-License-Identifier: MIT
#include "footprint.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <emcv/port/sss.h>

namespace emcv::demo {
namespace {

glm::vec3 world_box_centre(const mesh& m, const glm::mat4& model) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const vertex& v : m.vertices) {
        const glm::vec3 p(model * glm::vec4(v.position, 1.0f));
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    return 0.5f * (lo + hi);
}

}  // namespace

std::vector<scattering_footprint> scattering_footprints(const scene& s, int frame, int width, int height) {
    std::vector<scattering_footprint> out;
    const auto [eye, target] = s.view.at(frame);
    const glm::vec3 forward = glm::normalize(target - eye);
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    // P00 = cot(fov_x / 2) = cot(fov_y / 2) / aspect for a symmetric perspective projection.
    const float p00 = 1.0f / (std::tan(glm::radians(0.5f * s.view.fov_y_degrees)) * aspect);
    for (const object& o : s.objects) {
        const material& mat = s.materials[static_cast<std::size_t>(o.material)];
        if (!mat.scatters()) continue;
        scattering_footprint f;
        f.object = o.name;
        const float d_max = port::emcv_sss_widest(port::emcv_sss_shape_distance(mat.mean_free_path_mm, mat.albedo));
        f.radius_mm = port::emcv_burley_sample_exact(footprint_energy_fraction, d_max);
        const float z_view = glm::dot(world_box_centre(s.meshes[static_cast<std::size_t>(o.mesh)], o.model) - eye, forward);
        f.pixels_per_mm = z_view > 0.0f ? port::emcv_sss_pixels_per_mm(p00, static_cast<float>(width), z_view, s.mm_per_unit)
                                        : 0.0f;  // behind the camera: not on screen
        f.radius_pixels = f.radius_mm * f.pixels_per_mm;
        out.push_back(f);
    }
    return out;
}

}  // namespace emcv::demo
