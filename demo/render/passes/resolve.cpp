// SPDX-License-Identifier: MIT
// resolve: the temporal resolve of the composite's image (--resolve taa): last frame's resolved image,
// reprojected, moved by its guide's change, clipped to this frame's neighbourhood and blended with this frame's
// (resolve.comp.glsl).
#include "passes.hpp"

#include "emcv/port/bindings.h"
#include "render/bindings.h"

// Image units (render/bindings.h): below the guaranteed minimum, and distinct within the pass.
static_assert(EMCV_RENDER_IMG_RESOLVE_HISTORY < EMCV_MAX_IMAGE_UNITS && EMCV_RENDER_IMG_RESOLVED < EMCV_MAX_IMAGE_UNITS &&
              EMCV_RENDER_IMG_RESOLVE_GUIDE < EMCV_MAX_IMAGE_UNITS);
static_assert(EMCV_RENDER_IMG_RESOLVE_GUIDE != EMCV_RENDER_IMG_RESOLVE_HISTORY &&
              EMCV_RENDER_IMG_RESOLVE_GUIDE != EMCV_RENDER_IMG_RESOLVED &&
              EMCV_RENDER_IMG_RESOLVE_HISTORY != EMCV_RENDER_IMG_RESOLVED);

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
    if (r.resolve_guide.id() != 0) {  // without jitter (make_resolve_targets): the shader's guided()
        glBindTextureUnit(EMCV_RENDER_TEX_RESOLVE_GUIDE, r.resolve_guide_previous.id());
        glBindImageTexture(EMCV_RENDER_IMG_RESOLVE_GUIDE, r.resolve_guide.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY,
                           GL_RGBA16F);
    }
    glDispatchCompute(c.groups_x, c.groups_y, 1);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
}

}  // namespace emcv::demo::passes
