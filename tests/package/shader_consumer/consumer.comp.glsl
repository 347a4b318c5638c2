// An engine's compute shader that takes the installed emcv port as it is: glslang resolves the includes
// (GL_GOOGLE_include_directive, include root <prefix>/include), no emcv tool or build tree involved.
// Per pixel: a Burley-sampled scattering estimate f against the unscattered irradiance G, the control
// variate's coefficient from the EMCM of (f, G) (supp. Eq. 21, Eq. 31), the residual's moving variance and
// the next frame's sample count (SPVG).
#version 450 core
#extension GL_GOOGLE_include_directive : require
#include "emcv/port/bindings.h"
#include "emcv/port/burley.h"
#include "emcv/port/cv.h"
#include "emcv/port/ema.h"
#include "emcv/port/hash.h"
#include "emcv/port/samples.h"

layout(local_size_x = EMCV_WORKGROUP_SIZE_X) in;

layout(std430, EMCV_LAYOUT_BINDING(0)) readonly buffer Irradiance { float irradiance[]; };  // one row
layout(std430, EMCV_LAYOUT_BINDING(1)) buffer Covariance { EmcvEmcm2 covariance[]; };        // per pixel
layout(std430, EMCV_LAYOUT_BINDING(2)) buffer Residual { EmcvMovingStats residual[]; };      // per pixel
layout(std430, EMCV_LAYOUT_BINDING(3)) buffer SampleCount { int sample_count[]; };           // per pixel

void main() {
    const uint pixel = gl_GlobalInvocationID.x;
    const int width = irradiance.length();
    const float g = irradiance[pixel];
    const int n = max(sample_count[pixel], 1);
    float f = 0.0f;  // f = mean of E(x + r) 2 pi r R(r) / p(r) over r ~ SPVG's approximate inverse CDF
    for (int i = 0; i < n; ++i) {
        const vec2 u = emcv_hammersley(uint(i) ^ emcv_pcg(pixel), uint(n));
        const float r = emcv_burley_sample_spvg(u.x, 1.0f);
        const int x = clamp(int(pixel) + int(round(u.y < 0.5f ? -r : r)), 0, width - 1);
        f += irradiance[x] * 2.0f * emcv_burley_pi() * emcv_burley_profile_r(r, 1.0f) /
             (emcv_burley_pdf(r, 1.0f) * float(n));
    }
    EmcvEmcm2 cov = covariance[pixel];
    EmcvMovingStats res = residual[pixel];
    const float alpha = emcv_cv_coefficient_emcm2(cov);  // alpha_{t-1}
    emcv_moving_stats_push(res, emcv_cv_residual(f, alpha, g), 0.2f);
    emcv_emcm2_push(cov, vec2(f, g), 0.05f);
    covariance[pixel] = cov;
    residual[pixel] = res;
    sample_count[pixel] = emcv_sample_count(res.variance, 1e-4f, 8, 64);  // for the next frame
}
