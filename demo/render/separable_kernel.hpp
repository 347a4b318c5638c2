// SPDX-License-Identifier: MIT
// Separable SSS kernel (Jimenez 2015, docs/frame.md) built on the CPU from a material's Burley profile.
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace emcv::demo {

struct separable_kernel {
    float half_width_mm = 0.0f;   ///< X: the outermost tap's offset
    std::vector<glm::vec4> taps;  ///< rgb weight (each channel sums to 1), w offset in mm; taps[0] is the centre
};

/// `taps` (odd, >= 3) offsets x_i = X sign(o_i) o_i^2, o_i = -1 + 2 i / (taps - 1) (Jimenez's quadratic
/// spacing, EXPONENT 2), X = the radius holding 99% of the widest channel's profile. Weight of tap i in
/// channel c: the mass of the channel's 2-D Burley profile (shape distance d_c) in the strip of x between the
/// midpoints to the neighbouring taps (the outermost strips reach to infinity), so each channel sums to 1 and
/// the kernel is the profile's 1-D marginal, what a separable pass along x must convolve with.
separable_kernel make_separable_kernel(const glm::vec3& shape_distance_mm, int taps);

/// P(X > t) for t >= 0, X = r cos(theta): r from the Burley radial pdf of shape distance d, theta uniform.
double burley_marginal_tail(double t, double d);

}  // namespace emcv::demo
