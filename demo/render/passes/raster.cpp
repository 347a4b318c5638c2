// SPDX-License-Identifier: MIT
// The rasterising passes: gbuffer (every object into the G-buffer) and shadow (one light's depth map).
#include "passes.hpp"

#include "render/bindings.h"

namespace emcv::demo::passes {

void gbuffer(const frame_context& c) {
    const gpu_resources& r = c.res;
    glBindFramebuffer(GL_FRAMEBUFFER, r.gbuffer_fbo.id());
    glViewport(0, 0, r.width, r.height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const GLuint zero_u[4] = {0u, 0u, 0u, 0u};
    const float far_depth = 1.0f;
    for (GLint i = 0; i < 5; ++i) {
        if (i == 3) glClearNamedFramebufferuiv(r.gbuffer_fbo.id(), GL_COLOR, i, zero_u);  // material ids (R8UI)
        else glClearNamedFramebufferfv(r.gbuffer_fbo.id(), GL_COLOR, i, zero);
    }
    glClearNamedFramebufferfv(r.gbuffer_fbo.id(), GL_DEPTH, 0, &far_depth);
    c.programs.gbuffer.use();
    r.draw_objects(true);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void shadow(const frame_context& c, const planned_pass& p) {
    const gpu_resources& r = c.res;
    c.programs.shadow.use();
    glViewport(0, 0, shadow_resolution, shadow_resolution);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.5f, 2.0f);
    const gl::framebuffer& fbo = r.shadow_fbos[p.layer];
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    const float far_depth = 1.0f;
    glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &far_depth);
    glBindBufferRange(GL_UNIFORM_BUFFER, EMCV_RENDER_PASS, r.pass_ubo.id(), r.pass_offset(p.layer),
                      sizeof(gpu::pass_block));
    r.draw_objects(false);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace emcv::demo::passes
