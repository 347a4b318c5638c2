// SPDX-License-Identifier: MIT
// resolve: the temporal resolve of the composite's image (--resolve taa): last frame's resolved image,
// reprojected and clipped to this frame's neighbourhood, blended with this frame's (resolve.comp.glsl).
#include "passes.hpp"

#include "render/bindings.h"

namespace emcv::demo::passes {

void resolve(const frame_context& c) {
    const gpu_resources& r = c.res;
    c.programs.resolve.use();
    glBindTextureUnit(EMCV_RENDER_TEX_RESOLVE_CURRENT, r.linear_out.id());
    glBindTextureUnit(EMCV_RENDER_TEX_SSS_IN, r.sss_out.id());
    glBindTextureUnit(EMCV_RENDER_TEX_SSS_COUNT, r.counts.id());
    glBindTextureUnit(EMCV_RENDER_TEX_RESOLVE_HISTORY, r.resolve_history_previous.id());
    glBindImageTexture(EMCV_RENDER_IMG_RESOLVE_HISTORY, r.resolve_history.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindImageTexture(EMCV_RENDER_IMG_RESOLVED, r.resolved_display.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
    glDispatchCompute(c.groups_x, c.groups_y, 1);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
}

}  // namespace emcv::demo::passes
