// SPDX-License-Identifier: MIT
// Depth-aware rejection: light does not scatter across a depth step (r_e = sqrt(r^2 + dz^2), docs/frame.md).
#include <catch2/catch_test_macros.hpp>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "../gpu/gl_test_support.hpp"
#include "gl/debug.hpp"
#include "render/renderer.hpp"
#include "render_test_support.hpp"
#include "scene/procedural.hpp"

using namespace emcv::demo;

namespace {

constexpr int size = 64;

/// Two SSS half-planes facing the camera, meeting on the view axis: A (x < 0) at depth 0, lit by a spot whose
/// cone ends before the seam, and B (x > 0) `gap` world units further back, unlit. 10 mm per unit, mean
/// free path 1 mm (d_max = 0.29 mm, 1.1 px at the seam).
scene step_scene(float gap) {
    scene s = emcv::test::lit_sss_plane(1.0f);
    s.meshes = {make_plane(2.0f, 2.0f, 1)};
    const glm::mat4 face_camera = glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1.0f, 0.0f, 0.0f));
    object a;
    a.name = "near";
    a.model = glm::translate(glm::mat4(1.0f), glm::vec3(-1.0f, 0.0f, 0.0f)) * face_camera;
    object b;
    b.name = "far";
    b.model = glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, -gap)) * face_camera;
    s.objects = {a, b};
    light spot;
    spot.name = "spot";
    spot.type = light::kind::spot;
    spot.position = glm::vec3(-1.0f, 0.0f, 2.0f);
    spot.direction = glm::vec3(0.0f, 0.0f, -1.0f);
    // Lit out to x = -1 + 2 tan(20 deg) = -0.27 on A (2.7 mm short of the seam) and, at B's depth for the
    // largest gap, to -1 + 2.5 tan(20 deg) = -0.09: B is never lit directly.
    spot.inner_cone_degrees = 17.0f;
    spot.outer_cone_degrees = 20.0f;
    spot.intensity.value = 20.0f;
    s.lights = {spot};
    return s;
}

/// Light that scattering moved into B's first 8 columns right of the seam: sum of (scattered - unscattered).
double bleed_into_far_plane(const scene& s) {
    render_options options;
    options.width = size;
    options.height = size;
    renderer unscattered(s, method{method::kind::diffuse, 0}, options);
    unscattered.render(0);
    renderer scattered(s, make_reference(1024), options);
    scattered.render(0);
    const emcv::gl::float_image u = unscattered.linear();
    const emcv::gl::float_image v = scattered.linear();
    double bleed = 0.0;
    for (int y = 8; y < size - 8; ++y) {
        for (int x = size / 2; x < size / 2 + 8; ++x) {
            const std::size_t i = 4 * (std::size_t(y) * size + std::size_t(x));
            for (std::size_t c = 0; c < 3; ++c) bleed += double(v.pixels[i + c]) - double(u.pixels[i + c]);
        }
    }
    return bleed;
}

}  // namespace

TEST_CASE("light does not scatter across a depth step") {
    // Coplanar, A's light reaches B's first columns from 2.7 mm and more away (~10 d, the slow e^{-r/3d} term
    // of the profile). With B 0.5 units = 5 mm behind, a sample from A at radius r has r_e = sqrt(r^2 + 25):
    // its weight r_e R(r_e) / p(r) relative to the coplanar r R(r) / p(r) is about e^{-(r_e - r) / 3d}, and
    // r_e - r = 2.4 mm = 8.4 d at r = 4 mm (e^{-2.8} = 0.06), 2.1 mm = 7.3 d at r = 5 mm (0.09); radii
    // beyond carry little weight. B's own samples keep their weight, so the step must cut the bleed to
    // < 1/10 of the coplanar bleed. Without the depth term (r_e = r) the two bleeds would be about equal.
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    const double coplanar = bleed_into_far_plane(step_scene(0.0f));
    const double stepped = bleed_into_far_plane(step_scene(0.5f));
    INFO("bleed into the far plane's first columns: coplanar " << coplanar << ", behind a 5 mm step " << stepped);
    CHECK(coplanar > 0.0);
    CHECK(std::abs(stepped) < 0.1 * coplanar);
    CHECK(messenger.error_count() == 0);
}
