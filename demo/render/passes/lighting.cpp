// SPDX-License-Identifier: MIT
// lighting: diffuse irradiance without albedo and specular, kept apart (the SSS passes scatter the first).
#include "passes.hpp"

#include "render/bindings.h"

namespace emcv::demo::passes {

void lighting(const frame_context& c) {
    const gpu_resources& r = c.res;
    c.programs.lighting.use();
    glBindImageTexture(EMCV_RENDER_IMG_DIFFUSE, r.lit_diffuse.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(EMCV_RENDER_IMG_SPECULAR, r.lit_specular.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute(c.groups_x, c.groups_y, 1);
    image_barrier_for_reads();
}

}  // namespace emcv::demo::passes
