// SPDX-License-Identifier: MIT
// Scenes built in code for the render tests (small, fixed), and image checks shared by them.
#pragma once

#include <string>

#include "gl/image_io.hpp"
#include "scene/scene.hpp"

namespace emcv::test {

/// An SSS sphere (skin-like mean free path) on a diffuse floor, a shadow-casting directional key light and a
/// spot light; mm_per_unit 100 (a 20 cm sphere), camera 1 m away.
emcv::demo::scene sphere_on_floor();

/// A flat SSS plane filling the view, facing the camera, under one directional light at normal incidence and
/// no ambient: uniform irradiance on every SSS pixel (the energy test).
emcv::demo::scene lit_sss_plane(float mean_free_path_mm);

/// The same floor and lights as sphere_on_floor with a plain diffuse sphere (nothing scatters).
emcv::demo::scene no_sss();

/// sphere_on_floor with the camera turned away from the sphere (the SSS object is outside the frustum).
emcv::demo::scene sss_outside_view();

/// Number of NaN or infinite values in the image.
std::size_t count_non_finite(const emcv::gl::float_image& image);

}  // namespace emcv::test
