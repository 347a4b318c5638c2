// SPDX-License-Identifier: MIT
// composite: post-scatter albedo * scattered (or unscattered) diffuse + specular, then the display encoding
// (tonemap, sRGB) into the RGBA8 display image; the linear HDR result beside it.
#include "passes.hpp"

#include "render/bindings.h"

namespace emcv::demo::passes {

void composite(const frame_context& c) {
    const gpu_resources& r = c.res;
    c.programs.composite.use();
    glBindTextureUnit(EMCV_RENDER_TEX_SSS_IN, r.sss_out.id());
    glBindImageTexture(EMCV_RENDER_IMG_LINEAR, r.linear_out.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(EMCV_RENDER_IMG_DISPLAY, r.display_out.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
    glDispatchCompute(c.groups_x, c.groups_y, 1);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
}

}  // namespace emcv::demo::passes
