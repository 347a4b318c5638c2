// SPDX-License-Identifier: MIT
// How large scattering is on screen: per SSS object, the 99.7% radius of its widest Burley profile in mm and
// in pixels at the object's centre (docs/scenes.md chooses the built-in scenes' scales with it; tests/scene
// checks that `far` stays under a pixel and the others span several pixels).
#pragma once

#include <string>
#include <vector>

#include "scene.hpp"

namespace emcv::demo {

struct scattering_footprint {
    std::string object;
    float radius_mm = 0.0f;      ///< r with F(r) = 0.997 for the widest channel: about 16.6 d_max
    float pixels_per_mm = 0.0f;  ///< at the centre of the object's bounding box
    float radius_pixels = 0.0f;
};

/// The fraction of the profile's energy within radius_mm.
constexpr float footprint_energy_fraction = 0.997f;

/// One entry per object with a scattering material, camera at `frame`, viewport width x height pixels. Uses
/// the material's albedo for s(A); an albedo texture, which multiplies it per pixel, is not sampled here.
std::vector<scattering_footprint> scattering_footprints(const scene& s, int frame, int width, int height);

}  // namespace emcv::demo
