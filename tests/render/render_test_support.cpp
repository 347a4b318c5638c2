// SPDX-License-Identifier: MIT
#include "render_test_support.hpp"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/procedural.hpp"

namespace emcv::test {

using namespace emcv::demo;

namespace {

material skin() {
    material m;
    m.name = "skin";
    m.type = material::kind::sss;
    m.albedo = glm::vec3(0.91f, 0.34f, 0.27f);              // UE's default surface albedo (docs/frame.md)
    m.mean_free_path_mm = glm::vec3(26.75f, 2.38f, 1.93f) * 0.5f;  // UE's default DMFP colour x distance, halved
    m.specular = 0.3f;
    m.roughness = 0.4f;
    return m;
}

material grey() {
    material m;
    m.name = "grey";
    m.albedo = glm::vec3(0.5f);
    return m;
}

light key_light() {
    light l;
    l.name = "key";
    l.type = light::kind::directional;
    l.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.5f));
    l.intensity.value = 3.0f;
    l.casts_shadow = true;
    return l;
}

light spot_light() {
    light l;
    l.name = "spot";
    l.type = light::kind::spot;
    l.position = glm::vec3(1.0f, 1.5f, 1.0f);
    l.direction = glm::normalize(glm::vec3(0.0f, 0.0f, 0.0f) - l.position);
    l.intensity.value = 4.0f;
    l.color = glm::vec3(1.0f, 0.9f, 0.8f);
    l.casts_shadow = true;
    return l;
}

}  // namespace

scene sphere_on_floor() {
    scene s;
    s.name = "sphere-on-floor";
    s.mm_per_unit = 100.0f;
    s.ambient = glm::vec3(0.05f);
    s.background = glm::vec3(0.1f, 0.1f, 0.12f);
    s.view.position = glm::vec3(0.0f, 0.4f, 1.2f);
    s.view.target = glm::vec3(0.0f, 0.0f, 0.0f);
    s.view.fov_y_degrees = 35.0f;
    s.meshes.push_back(make_sphere(0.2f, 48, 24));
    s.meshes.push_back(make_plane(3.0f, 3.0f, 1));
    s.materials = {skin(), grey()};
    object sphere;
    sphere.name = "sphere";
    sphere.mesh = 0;
    sphere.material = 0;
    sphere.model = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 0.0f));
    object floor;
    floor.name = "floor";
    floor.mesh = 1;
    floor.material = 1;
    floor.model = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -0.2f, 0.0f));
    s.objects = {sphere, floor};
    s.lights = {key_light(), spot_light()};
    return s;
}

scene lit_sss_plane(float mean_free_path_mm) {
    scene s;
    s.name = "lit-sss-plane";
    s.mm_per_unit = 10.0f;
    s.view.position = glm::vec3(0.0f, 0.0f, 3.0f);
    s.view.target = glm::vec3(0.0f);
    s.view.fov_y_degrees = 30.0f;
    s.meshes.push_back(make_plane(4.0f, 4.0f, 1));
    material m = skin();
    m.specular = 0.0f;
    m.mean_free_path_mm = glm::vec3(mean_free_path_mm);
    s.materials = {m};
    object plane;
    plane.name = "plane";
    // make_plane faces +y; rotate it to face +z (the camera).
    plane.model = glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1.0f, 0.0f, 0.0f));
    s.objects = {plane};
    light l;
    l.name = "sun";
    l.direction = glm::vec3(0.0f, 0.0f, -1.0f);
    l.intensity.value = 2.0f;
    s.lights = {l};
    return s;
}

scene no_sss() {
    scene s = sphere_on_floor();
    s.name = "no-sss";
    s.materials[0].type = material::kind::diffuse;
    for (light& l : s.lights) l.casts_shadow = false;
    return s;
}

scene sss_outside_view() {
    scene s = sphere_on_floor();
    s.name = "sss-outside-view";
    s.view.position = glm::vec3(0.0f, 0.4f, 1.2f);
    s.view.target = glm::vec3(0.0f, 0.4f, 3.0f);  // looking away from the sphere
    return s;
}

std::size_t count_non_finite(const emcv::gl::float_image& image) {
    std::size_t n = 0;
    for (float v : image.pixels) n += std::isfinite(v) ? 0u : 1u;
    return n;
}

}  // namespace emcv::test
