// SPDX-License-Identifier: MIT
// One planned pass -> its module (passes.hpp).
#include "passes.hpp"

#include "render/bindings.h"

namespace emcv::demo::passes {

void record(const planned_pass& p, const frame_context& c) {
    switch (p.id) {
        case pass_id::gbuffer: gbuffer(c); return;
        case pass_id::shadow: shadow(c, p); return;
        case pass_id::lighting: lighting(c); return;
        case pass_id::sss_adaptive_samples: sss_adaptive_samples(c); return;
        case pass_id::sss_burley: sss_burley(c, p.burley); return;
        case pass_id::sss_separable_h: sss_separable(c, 0); return;
        case pass_id::sss_separable_v: sss_separable(c, 1); return;
        case pass_id::composite: composite(c); return;
        case pass_id::resolve: resolve(c); return;
    }
}

void bind_frame_resources(const frame_context& c) {
    const gpu_resources& r = c.res;
    glBindBufferBase(GL_UNIFORM_BUFFER, EMCV_RENDER_FRAME, r.frame_ubo.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EMCV_RENDER_LIGHTS, r.lights_ssbo.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EMCV_RENDER_MATERIALS, r.materials_ssbo.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EMCV_RENDER_OBJECTS, r.objects_ssbo.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EMCV_RENDER_STATS, r.stats_ssbo.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EMCV_RENDER_TILES, r.tiles_ssbo.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, EMCV_RENDER_KERNELS, r.kernels_ssbo.id());
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, r.tiles_ssbo.id());
    glBindVertexArray(r.vao.id());
    glBindTextureUnit(EMCV_RENDER_TEX_SHADOWS, r.shadow_maps.id());
    glBindTextureUnit(EMCV_RENDER_TEX_DEPTH, r.gb_depth.id());
    glBindTextureUnit(EMCV_RENDER_TEX_NORMAL, r.gb_normal.id());
    glBindTextureUnit(EMCV_RENDER_TEX_ALBEDO, r.gb_albedo.id());
    glBindTextureUnit(EMCV_RENDER_TEX_MATERIAL, r.gb_material.id());
    glBindTextureUnit(EMCV_RENDER_TEX_MOTION, r.gb_motion.id());
    glBindTextureUnit(EMCV_RENDER_TEX_DIFFUSE, r.lit_diffuse.id());
    glBindTextureUnit(EMCV_RENDER_TEX_SPECULAR, r.lit_specular.id());
}

void image_barrier_for_reads() { glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT); }

}  // namespace emcv::demo::passes
