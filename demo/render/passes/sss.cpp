// SPDX-License-Identifier: MIT
// The SSS passes: sss-burley, sss-separable-h/-v, and the adaptive methods' own sss-burley program, after their
// sss-adaptive-samples in budget mode (demo/render/adaptive). They dispatch indirectly over the SSS tiles that the
// lighting pass listed (render/tiles.h).
#include "passes.hpp"

#include <stdexcept>

#include "adaptive/bindings.h"
#include "emcv/port/bindings.h"
#include "render/adaptive/history.hpp"
#include "render/bindings.h"

// Image units (render/bindings.h): below the guaranteed minimum, and distinct within each pass.
static_assert(EMCV_RENDER_IMG_DIFFUSE < EMCV_MAX_IMAGE_UNITS && EMCV_RENDER_IMG_SPECULAR < EMCV_MAX_IMAGE_UNITS &&
              EMCV_RENDER_IMG_SSS_OUT < EMCV_MAX_IMAGE_UNITS && EMCV_RENDER_IMG_COUNT < EMCV_MAX_IMAGE_UNITS &&
              EMCV_RENDER_IMG_LINEAR < EMCV_MAX_IMAGE_UNITS && EMCV_RENDER_IMG_DISPLAY < EMCV_MAX_IMAGE_UNITS);
static_assert(EMCV_RENDER_IMG_DIFFUSE != EMCV_RENDER_IMG_SPECULAR && EMCV_RENDER_IMG_SSS_OUT != EMCV_RENDER_IMG_COUNT &&
              EMCV_RENDER_IMG_LINEAR != EMCV_RENDER_IMG_DISPLAY);

namespace emcv::demo::passes {

// frame_planner plans the adaptive passes only for the adaptive methods (method table), and the renderer makes a
// history for exactly those: c.history is set wherever they run. The SSS passes dispatch indirectly from the
// tile list that the lighting pass wrote (bound once per frame, passes.hpp).

namespace {

/// The previous frame's G-buffer, which the current one ping-pongs with (resources.hpp, swap_gbuffer): what an
/// adaptive method's history reprojection tests a surface against.
void bind_previous_gbuffer(const gpu_resources& r) {
    glBindTextureUnit(EMCV_ADAPTIVE_TEX_PREV_DEPTH, r.prev_gb_depth.id());
    glBindTextureUnit(EMCV_ADAPTIVE_TEX_PREV_NORMAL, r.prev_gb_normal.id());
    glBindTextureUnit(EMCV_ADAPTIVE_TEX_PREV_MATERIAL, r.prev_gb_material.id());
}

}  // namespace

void sss_adaptive_samples(const frame_context& c) {
    bind_previous_gbuffer(c.res);
    c.history->record_samples();
}

void sss_burley(const frame_context& c, burley_variant variant) {
    const gpu_resources& r = c.res;
    // An adaptive method's burley program takes N per pixel (under a quality target it plans N itself from
    // the reprojected history) and updates the history it binds (the adaptive methods always have one:
    // frame_context's note above); it reads its own output back (read-write).
    if (c.history) {
        bind_previous_gbuffer(r);
        c.history->use_burley(variant);
    } else {
        c.programs.burley.use();
    }
    glBindImageTexture(EMCV_RENDER_IMG_COUNT, r.counts.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32UI);
    glBindImageTexture(EMCV_RENDER_IMG_SSS_OUT, r.sss_out.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
    glDispatchComputeIndirect(0);
    // A burley pass that planned the next frame histogrammed that frame's variances: solved now, in this pass.
    if (variant == burley_variant::plans_next) c.history->solve_budget();
    image_barrier_for_reads();
    // the stats block is read back after the frame; an adaptive history may be (history::read)
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

void sss_separable(const frame_context& c, int direction) {
    const gpu_resources& r = c.res;
    c.programs.separable.use();
    const GLuint source = direction == 0 ? r.lit_diffuse.id() : r.sss_temp.id();
    const GLuint target = direction == 0 ? r.sss_temp.id() : r.sss_out.id();
    glBindTextureUnit(EMCV_RENDER_TEX_SSS_IN, source);
    glBindImageTexture(EMCV_RENDER_IMG_SSS_OUT, target, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindBufferRange(GL_UNIFORM_BUFFER, EMCV_RENDER_PASS, r.pass_ubo.id(), r.pass_offset(r.separable_slot(direction)),
                      sizeof(gpu::pass_block));
    glDispatchComputeIndirect(0);
    image_barrier_for_reads();
}

}  // namespace emcv::demo::passes
